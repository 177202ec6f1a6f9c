//! The blocking shell of the [`cyclic`](super::cyclic) planner on the CANopen network manager:
//! the manager produces SYNC at the period, each axis answers every SYNC with a TPDO (statusword
//! and position actual value), and on each answer the shell sends the axis's next RPDO
//! (controlword and set point), which the drive takes at the next SYNC.
//!
//! [`CyclicRun::start`] refuses a mode an axis does not list in 6502h before anything is sent,
//! then sets the mode (6060h) and the interpolation period (60C2h) by SDO and starts SYNC.
//! [`CyclicRun::run`] first enables every axis through its RPDO, then sends the trajectory's
//! samples; a fault, following error or loss of feedback quick-stops every axis and ends the run
//! with a typed [`CyclicError`].
//!
//! The drives' PDOs must be mapped so (the example axis's defaults, `examples/csp_axis`): the
//! RPDO of `rpdo_cob_id` carries the controlword then the set point (607Ah, 60FFh or 6071h), with
//! transmission type 0-240; the TPDO `tpdo` carries the statusword then 6064h, type 1.

use core::fmt;
use core::time::Duration;
use std::time::Instant;
use std::vec::Vec;

use super::cycle_stats::CycleStats;
use super::cyclic::{CyclicFailure, CyclicMode, Feedback};
use super::cyclic_steps::{setup_writes, Axes, Axis};
use super::quirks::Quirks;
use crate::canopen::emcy::Emcy;
use crate::canopen::network::{Network, Subscription};
use crate::canopen::{NodeId, SdoBus};
use crate::error::BusError;

/// How one axis is reached: its node and PDOs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AxisLink {
    /// The node.
    pub node: NodeId,
    /// The COB-ID of the RPDO carrying the controlword and the set point.
    pub rpdo_cob_id: u16,
    /// The TPDO (1..=4) carrying the statusword and the position actual value.
    pub tpdo: u8,
}

/// How a run goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CyclicConfig {
    /// The mode of every axis.
    pub mode: CyclicMode,
    /// The SYNC and interpolation period.
    pub period: Duration,
    /// The axes' deviations from CiA 402.
    pub quirks: Quirks,
    /// The longest the axes may take to reach operation enabled.
    pub enable_within: Duration,
    /// The longest an axis may stay silent before the run fails with
    /// [`CyclicError::FeedbackLost`]: some periods, more on a machine that is not real-time
    /// (SYNCs whose feedback came late are counted as missed cycles meanwhile).
    pub feedback_within: Duration,
}

/// Why a cyclic run failed.
#[derive(Debug, Clone, PartialEq)]
pub enum CyclicError {
    /// An axis cannot run or stopped the run (mode not supported, fault, following error...).
    Axis {
        /// The axis's node.
        node: NodeId,
        /// What happened.
        failure: CyclicFailure,
        /// The last emergency the node sent during the run, if any (the fault's cause).
        emcy: Option<Emcy>,
    },
    /// An axis sent no TPDO within `feedback_within`.
    FeedbackLost {
        /// The silent node.
        node: NodeId,
    },
    /// The axes were not all operation enabled within `enable_within`.
    EnableTimeout {
        /// The first axis still enabling.
        node: NodeId,
    },
    /// An SDO transfer or the bus failed.
    Bus(BusError),
}

impl From<BusError> for CyclicError {
    fn from(error: BusError) -> Self {
        CyclicError::Bus(error)
    }
}

impl fmt::Display for CyclicError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CyclicError::Axis {
                node,
                failure,
                emcy,
            } => {
                write!(f, "node {}: {failure:?}", node.0)?;
                match emcy {
                    Some(emcy) => write!(f, " (EMCY {:#06x})", emcy.code),
                    None => Ok(()),
                }
            }
            CyclicError::FeedbackLost { node } => {
                write!(f, "node {} stopped sending its TPDO", node.0)
            }
            CyclicError::EnableTimeout { node } => {
                write!(f, "node {} did not reach operation enabled in time", node.0)
            }
            CyclicError::Bus(e) => write!(f, "cyclic run: {e}"),
        }
    }
}

impl std::error::Error for CyclicError {}

/// A cyclic synchronous run of several axes on one network.
#[derive(Debug)]
pub struct CyclicRun<'n, B> {
    network: &'n Network<B>,
    axes: Axes<Subscription>,
}

/// Reads `index:sub` as a little-endian integer of up to 4 bytes.
fn read_u32<S: SdoBus>(sdo: &mut S, node: NodeId, index: u16, sub: u8) -> Result<u32, BusError> {
    let mut out = [0u8; 4];
    sdo.upload(node, index, sub, &mut out)?;
    Ok(u32::from_le_bytes(out))
}

impl<'n, B> CyclicRun<'n, B> {
    /// Checks every axis lists the mode (6502h) before anything is sent, then sets the mode,
    /// the interpolation period, subscribes to the TPDOs and starts SYNC at the period. The
    /// nodes must be Operational for their PDOs to run.
    pub fn start(
        network: &'n Network<B>,
        links: &[AxisLink],
        config: CyclicConfig,
    ) -> Result<Self, CyclicError> {
        let mut axes = Vec::with_capacity(links.len());
        for link in links {
            let mut sdo = network.node(link.node);
            let supported = read_u32(&mut sdo, link.node, 0x6502, 0)?;
            // 6065h is optional: without it the master does not check the position.
            let window = read_u32(&mut sdo, link.node, 0x6065, 0).ok();
            axes.push(Axis::new(*link, &config, supported, window)?);
        }
        for link in links {
            let mut sdo = network.node(link.node);
            for (index, sub, value) in setup_writes(&config) {
                sdo.download(link.node, index, sub, &value)?;
            }
        }
        let axes = Axes::start(network, config, axes);
        Ok(Self { network, axes })
    }

    /// The last feedback of each axis, in the order of the links.
    pub fn feedback(&self) -> Vec<Feedback> {
        self.axes.feedback()
    }

    /// Enables every axis, then runs `cycles` cycles sending `sample(cycle, axis)` as each
    /// axis's set point (axis: the index of its link), and returns the cycle timing. The axes
    /// hold the last set point after the run. A failure quick-stops every axis first.
    pub fn run(
        &mut self,
        cycles: u64,
        mut sample: impl FnMut(u64, usize) -> i32,
    ) -> Result<CycleStats, CyclicError> {
        let mut run = self.axes.cycles(cycles);
        while run.running() {
            let cycle = self
                .receive()
                .and_then(|()| self.axes.step(&mut run, &mut sample, self.network));
            if let Err(error) = cycle {
                self.stop();
                return Err(error);
            }
        }
        Ok(run.stats())
    }

    /// Waits for every axis's TPDO of this SYNC; a TPDO queued behind a newer one is passed
    /// over (the newest is the state now).
    fn receive(&mut self) -> Result<(), CyclicError> {
        let timeout = self.axes.config.feedback_within;
        for (axis, events) in self.axes.each() {
            while !axis.take(events.recv(timeout)?.ok_or_else(|| axis.lost())?) {}
            axis.drain(core::iter::from_fn(|| events.try_recv()));
        }
        Ok(())
    }

    /// Quick-stops every axis (holding its set point) and waits, up to `feedback_within`, for
    /// every TPDO to show it left operation enabled (a TPDO already queued may predate the
    /// stop); SYNC goes on until the run is dropped.
    pub fn stop(&mut self) {
        self.axes.stop(self.network);
        let until = Instant::now() + self.axes.config.feedback_within;
        while Instant::now() < until && self.axes.any_enabled() && self.receive().is_ok() {}
    }
}

impl<B> Drop for CyclicRun<'_, B> {
    /// Stops SYNC: the drives keep their last set point.
    fn drop(&mut self) {
        self.network.set_sync(None);
    }
}

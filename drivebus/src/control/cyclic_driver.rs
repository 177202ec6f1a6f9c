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
use super::cyclic::{Command, CyclicAxis, CyclicFailure, CyclicMode, Feedback};
use super::position::operation_enabled;
use super::quirks::Quirks;
use super::Millis;
use crate::canopen::emcy::Emcy;
use crate::canopen::network::{Network, NetworkEvent, Subscription};
use crate::canopen::{CanFrame, NodeId, SdoBus};
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

/// One axis of a run.
#[derive(Debug)]
struct Axis {
    link: AxisLink,
    planner: CyclicAxis,
    events: Subscription,
    last: Feedback,
    emcy: Option<Emcy>,
}

/// A cyclic synchronous run of several axes on one network.
#[derive(Debug)]
pub struct CyclicRun<'n, B> {
    network: &'n Network<B>,
    config: CyclicConfig,
    axes: Vec<Axis>,
    started: Instant,
}

/// Reads `index:sub` as a little-endian integer of up to 4 bytes.
fn read_u32<S: SdoBus>(sdo: &mut S, node: NodeId, index: u16, sub: u8) -> Result<u32, BusError> {
    let mut out = [0u8; 4];
    sdo.upload(node, index, sub, &mut out)?;
    Ok(u32::from_le_bytes(out))
}

/// The interpolation period 60C2h as (value, power of ten): whole milliseconds if it is, else
/// tenths of milliseconds.
fn interpolation_period(period: Duration) -> (u8, i8) {
    let micros = period.as_micros();
    if micros % 1000 == 0 && micros / 1000 <= u128::from(u8::MAX) {
        ((micros / 1000) as u8, -3)
    } else {
        ((micros / 100).min(u128::from(u8::MAX)) as u8, -4)
    }
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
        let mut planners = Vec::with_capacity(links.len());
        for link in links {
            let mut sdo = network.node(link.node);
            let supported = read_u32(&mut sdo, link.node, 0x6502, 0)?;
            // 6065h is optional: without it the master does not check the position.
            let window = read_u32(&mut sdo, link.node, 0x6065, 0).ok();
            let planner = CyclicAxis::new(config.mode, supported, config.quirks, window).map_err(
                |failure| CyclicError::Axis {
                    node: link.node,
                    failure,
                    emcy: None,
                },
            )?;
            planners.push(planner);
        }
        let (value, index) = interpolation_period(config.period);
        let mut axes = Vec::with_capacity(links.len());
        for (link, planner) in links.iter().zip(planners) {
            let mut sdo = network.node(link.node);
            sdo.download(link.node, 0x6060, 0, &config.mode.number().to_le_bytes())?;
            sdo.download(link.node, 0x60C2, 1, &[value])?;
            sdo.download(link.node, 0x60C2, 2, &index.to_le_bytes())?;
            axes.push(Axis {
                link: *link,
                planner,
                events: network.subscribe(link.node, 64),
                last: Feedback {
                    statusword: 0,
                    actual: 0,
                },
                emcy: None,
            });
        }
        network.set_sync(Some(config.period));
        Ok(Self {
            network,
            config,
            axes,
            started: Instant::now(),
        })
    }

    /// The last feedback of each axis, in the order of the links.
    pub fn feedback(&self) -> Vec<Feedback> {
        self.axes.iter().map(|a| a.last).collect()
    }

    /// Enables every axis, then runs `cycles` cycles sending `sample(cycle, axis)` as each
    /// axis's set point (axis: the index of its link), and returns the cycle timing. The axes
    /// hold the last set point after the run. A failure quick-stops every axis first.
    pub fn run(
        &mut self,
        cycles: u64,
        mut sample: impl FnMut(u64, usize) -> i32,
    ) -> Result<CycleStats, CyclicError> {
        let result = self.cycles(cycles, &mut sample);
        if result.is_err() {
            self.stop();
        }
        result
    }

    fn cycles(
        &mut self,
        cycles: u64,
        sample: &mut impl FnMut(u64, usize) -> i32,
    ) -> Result<CycleStats, CyclicError> {
        let enable_by = Instant::now() + self.config.enable_within;
        let mut stats = CycleStats::new(self.config.period);
        let mut cycle = 0u64;
        let mut previous: Option<Instant> = None;
        while cycle < cycles {
            self.receive()?;
            let received = Instant::now();
            let following = self.axes.iter().all(|a| a.planner.following());
            if following {
                if let Some(previous) = previous {
                    stats.record(received - previous);
                }
                previous = Some(received);
            } else if received >= enable_by {
                let node = self.axes.iter().find(|a| !a.planner.following());
                return Err(CyclicError::EnableTimeout {
                    node: node.map_or(NodeId(0), |a| a.link.node),
                });
            }
            let now = Millis(self.started.elapsed().as_millis() as u64);
            for (i, axis) in self.axes.iter_mut().enumerate() {
                let next = following.then(|| sample(cycle, i));
                let command = axis
                    .planner
                    .cycle(axis.last, next, now)
                    .map_err(|failure| CyclicError::Axis {
                        node: axis.link.node,
                        failure,
                        emcy: axis.emcy,
                    })?;
                send(self.network, axis, command)?;
            }
            if following {
                cycle += 1;
            }
        }
        Ok(stats)
    }

    /// Waits for every axis's TPDO of this SYNC; a TPDO queued behind a newer one is passed
    /// over (the newest is the state now).
    fn receive(&mut self) -> Result<(), CyclicError> {
        let timeout = self.config.feedback_within;
        for axis in &mut self.axes {
            let mut fresh = false;
            loop {
                let event = if fresh {
                    match axis.events.try_recv() {
                        Some(event) => event,
                        None => break,
                    }
                } else {
                    match axis.events.recv(timeout)? {
                        Some(event) => event,
                        None => {
                            return Err(CyclicError::FeedbackLost {
                                node: axis.link.node,
                            })
                        }
                    }
                };
                match event {
                    NetworkEvent::Pdo { number, frame } if number == axis.link.tpdo => {
                        if let Some(feedback) = Feedback::from_tpdo(frame.data()) {
                            axis.last = feedback;
                            fresh = true;
                        }
                    }
                    NetworkEvent::Emcy(emcy) => axis.emcy = Some(emcy),
                    _ => {}
                }
            }
        }
        Ok(())
    }

    /// Quick-stops every axis (holding its set point) and waits, up to `feedback_within`, for
    /// every TPDO to show it left operation enabled (a TPDO already queued may predate the
    /// stop); SYNC goes on until the run is dropped.
    pub fn stop(&mut self) {
        for axis in &self.axes {
            // A bus that fails now has nothing more to stop.
            let _ = send(self.network, axis, axis.planner.stop(axis.last));
        }
        let until = Instant::now() + self.config.feedback_within;
        while Instant::now() < until
            && self
                .axes
                .iter()
                .any(|a| operation_enabled(a.last.statusword))
            && self.receive().is_ok()
        {}
    }
}

impl<B> Drop for CyclicRun<'_, B> {
    /// Stops SYNC: the drives keep their last set point.
    fn drop(&mut self) {
        self.network.set_sync(None);
    }
}

/// Sends `command` in `axis`'s RPDO.
fn send<B>(network: &Network<B>, axis: &Axis, command: Command) -> Result<(), BusError> {
    let (payload, len) = command.rpdo_payload(axis.planner.mode());
    network.send(CanFrame::new(axis.link.rpdo_cob_id, &payload[..len])?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_interpolation_period_in_milliseconds_or_tenths() {
        assert_eq!(interpolation_period(Duration::from_millis(4)), (4, -3));
        assert_eq!(interpolation_period(Duration::from_micros(1_500)), (15, -4));
    }
}

//! The async shell of the [`cyclic`](super::cyclic) planner on the async network manager
//! ([`AsyncNetwork`]), features `async` and `canopen`: the run of the blocking
//! [`CyclicRun`](super::cyclic_driver::CyclicRun), awaited. The refusals, the SDO writes and
//! each cycle are the blocking shell's (`cyclic_steps`); only the reads and waits differ, the
//! waits on the network's own [`Timer`].
//!
//! [`AsyncCyclicRun::start`] refuses a mode an axis does not list in 6502h before anything is
//! sent, then sets the mode (6060h) and the interpolation period (60C2h) by SDO and starts SYNC.
//! [`AsyncCyclicRun::run`] first enables every axis through its RPDO, then sends the
//! trajectory's samples; a fault, following error or loss of feedback quick-stops every axis
//! and ends the run with a typed [`CyclicError`]. The network's router
//! ([`AsyncRouter::run`](crate::canopen::network::AsyncRouter::run)) must be polled meanwhile.
//!
//! A run future dropped before its end (a `select!` that chose another branch) sends no quick
//! stop: the axes keep the last set point, as when SYNC ends; call [`AsyncCyclicRun::stop`] to
//! stop them. Dropping the run stops SYNC.

use std::vec::Vec;

use super::cycle_stats::CycleStats;
use super::cyclic::Feedback;
use super::cyclic_driver::{AxisLink, CyclicConfig, CyclicError};
use super::cyclic_steps::{setup_writes, Axes, Axis};
use crate::asynch::{within, Timer};
use crate::canopen::network::{AsyncNetwork, AsyncNodeSdo, AsyncSubscription};
use crate::canopen::{AsyncSdoBus, NodeId};
use crate::error::BusError;

/// A cyclic synchronous run of several axes on one async network.
#[derive(Debug)]
pub struct AsyncCyclicRun<'n, T> {
    network: &'n AsyncNetwork<T>,
    axes: Axes<AsyncSubscription>,
}

/// Reads `index:sub` as a little-endian integer of up to 4 bytes.
async fn read_u32<T: Timer>(
    sdo: &mut AsyncNodeSdo<T>,
    node: NodeId,
    index: u16,
    sub: u8,
) -> Result<u32, BusError> {
    let mut out = [0u8; 4];
    sdo.upload(node, index, sub, &mut out).await?;
    Ok(u32::from_le_bytes(out))
}

impl<'n, T: Timer + Clone> AsyncCyclicRun<'n, T> {
    /// Checks every axis lists the mode (6502h) before anything is sent, then sets the mode,
    /// the interpolation period, subscribes to the TPDOs and starts SYNC at the period. The
    /// nodes must be Operational for their PDOs to run.
    pub async fn start(
        network: &'n AsyncNetwork<T>,
        links: &[AxisLink],
        config: CyclicConfig,
    ) -> Result<Self, CyclicError> {
        let mut axes = Vec::with_capacity(links.len());
        for link in links {
            let mut sdo = network.node(link.node);
            let supported = read_u32(&mut sdo, link.node, 0x6502, 0).await?;
            // 6065h is optional: without it the master does not check the position.
            let window = read_u32(&mut sdo, link.node, 0x6065, 0).await.ok();
            axes.push(Axis::new(*link, &config, supported, window)?);
        }
        for link in links {
            let mut sdo = network.node(link.node);
            for (index, sub, value) in setup_writes(&config) {
                sdo.download(link.node, index, sub, &value).await?;
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
    pub async fn run(
        &mut self,
        cycles: u64,
        mut sample: impl FnMut(u64, usize) -> i32,
    ) -> Result<CycleStats, CyclicError> {
        let mut run = self.axes.cycles(cycles);
        while run.running() {
            let cycle = match self.receive().await {
                Ok(()) => self.axes.step(&mut run, &mut sample, self.network),
                Err(error) => Err(error),
            };
            if let Err(error) = cycle {
                self.stop().await;
                return Err(error);
            }
        }
        Ok(run.stats())
    }

    /// Waits for every axis's TPDO of this SYNC; a TPDO queued behind a newer one is passed
    /// over (the newest is the state now).
    async fn receive(&mut self) -> Result<(), CyclicError> {
        let network = self.network;
        let timeout = self.axes.config.feedback_within;
        for (axis, events) in self.axes.each() {
            loop {
                let next = within(network.timer(), timeout, events.next()).await;
                if axis.take(next.map_err(|_| axis.lost())??) {
                    break;
                }
            }
            axis.drain(core::iter::from_fn(|| events.try_next()));
        }
        Ok(())
    }

    /// Quick-stops every axis (holding its set point) and waits, up to `feedback_within`, for
    /// every TPDO to show it left operation enabled (a TPDO already queued may predate the
    /// stop); SYNC goes on until the run is dropped.
    pub async fn stop(&mut self) {
        let network = self.network;
        self.axes.stop(network);
        let limit = self.axes.config.feedback_within;
        let settled = async { while self.axes.any_enabled() && self.receive().await.is_ok() {} };
        // Out of time: the stop was sent; the TPDOs only confirm it.
        let _ = within(network.timer(), limit, settled).await;
    }
}

impl<T> Drop for AsyncCyclicRun<'_, T> {
    /// Stops SYNC: the drives keep their last set point.
    fn drop(&mut self) {
        self.network.set_sync(None);
    }
}

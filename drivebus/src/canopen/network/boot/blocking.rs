//! The boot driven over the blocking [`Network`]: one node on the caller's thread, or every
//! node at once, a thread each.

use core::time::Duration;

use super::{BootReport, NodeBoot};
use crate::canopen::link::SdoBus as _;
use crate::canopen::network::Network;
use crate::error::BusError;

/// Boots one node as `plan` says, each request given `timeout`; a booted node with a heartbeat
/// is watched from then on ([`consumer_timeout`](super::consumer_timeout)).
pub fn boot_node<B>(network: &Network<B>, plan: &NodeBoot, timeout: Duration) -> BootReport {
    drive_boot!(network, plan, timeout)
}

/// Boots every node of `plans` at once (a thread each); the reports in the plans' order.
pub fn boot_all<B: Send>(
    network: &Network<B>,
    plans: &[NodeBoot],
    timeout: Duration,
) -> std::vec::Vec<BootReport> {
    std::thread::scope(|scope| {
        let running: std::vec::Vec<_> = plans
            .iter()
            .map(|plan| scope.spawn(move || boot_node(network, plan, timeout)))
            .collect();
        plans
            .iter()
            .zip(running)
            .map(|(plan, thread)| {
                thread.join().unwrap_or(BootReport {
                    node: plan.node,
                    device_type: None,
                    // The boot's thread panicked: nothing more is known.
                    result: Err(super::BootError::Step {
                        step: super::BootStep::Probe,
                        error: BusError::Closed,
                    }),
                    written: 0,
                    unchanged: 0,
                })
            })
            .collect()
    })
}

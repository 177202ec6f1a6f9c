//! The boot driven over the blocking [`Network`]: one node on the caller's thread, or every
//! node at once, a thread each.

use core::time::Duration;

use super::{Action, BootProcedure, BootReport, NodeBoot};
use crate::canopen::link::SdoBus;
use crate::canopen::network::Network;
use crate::error::BusError;

/// The value of an upload of at most 4 bytes, little-endian.
pub(super) fn value(out: [u8; 4], len: usize) -> u32 {
    let mut bytes = [0u8; 4];
    let len = len.min(4);
    bytes[..len].copy_from_slice(&out[..len]);
    u32::from_le_bytes(bytes)
}

/// Boots one node as `plan` says, each request given `timeout`; a booted node with a heartbeat
/// is watched from then on ([`consumer_timeout`](super::consumer_timeout)).
pub fn boot_node<B>(network: &Network<B>, plan: &NodeBoot, timeout: Duration) -> BootReport {
    let node = plan.node;
    let mut sdo = network.node(node).with_timeout(timeout);
    let mut procedure = BootProcedure::new(plan);
    loop {
        match procedure.action() {
            Action::Read { index, subindex } => {
                let mut out = [0u8; 4];
                let read: Result<usize, BusError> = sdo.upload(node, index, subindex, &mut out);
                procedure.read(read.map(|len| value(out, len)));
            }
            Action::Write {
                index,
                subindex,
                data,
            } => {
                let wrote = sdo.download(node, index, subindex, data);
                procedure.wrote(wrote);
            }
            Action::Nmt(command) => procedure.sent(network.nmt(command, Some(node))),
            Action::Finished => break,
        }
    }
    if let Some(timeout) = procedure.heartbeat_watch() {
        network.monitor_heartbeat(node, timeout);
    }
    procedure.report()
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
                })
            })
            .collect()
    })
}

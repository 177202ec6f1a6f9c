//! The boot driven over an [`AsyncNetwork`]: one node per future; join them to boot many at
//! once.

use core::time::Duration;

use super::blocking::value;
use super::{Action, BootProcedure, BootReport, NodeBoot};
use crate::asynch::Timer;
use crate::canopen::link::AsyncSdoBus;
use crate::canopen::network::AsyncNetwork;

/// Boots one node as `plan` says, each request given `timeout`; a booted node with a heartbeat
/// is watched from then on ([`consumer_timeout`](super::consumer_timeout)).
pub async fn boot_node_async<T: Timer + Clone>(
    network: &AsyncNetwork<T>,
    plan: &NodeBoot,
    timeout: Duration,
) -> BootReport {
    let node = plan.node;
    let mut sdo = network.node(node).with_timeout(timeout);
    let mut procedure = BootProcedure::new(plan);
    loop {
        match procedure.action() {
            Action::Read { index, subindex } => {
                let mut out = [0u8; 4];
                let read = sdo.upload(node, index, subindex, &mut out).await;
                procedure.read(read.map(|len| value(out, len)));
            }
            Action::Write {
                index,
                subindex,
                data,
            } => {
                let wrote = sdo.download(node, index, subindex, data).await;
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

//! The boot driven over an [`AsyncNetwork`]: one node per future; join them to boot many at
//! once.

use core::time::Duration;

use super::{BootReport, NodeBoot};
use crate::asynch::Timer;
use crate::canopen::link::AsyncSdoBus as _;
use crate::canopen::network::AsyncNetwork;

/// Boots one node as `plan` says, each request given `timeout`; a booted node with a heartbeat
/// is watched from then on ([`consumer_timeout`](super::consumer_timeout)).
pub async fn boot_node_async<T: Timer + Clone>(
    network: &AsyncNetwork<T>,
    plan: &NodeBoot,
    timeout: Duration,
) -> BootReport {
    drive_boot!(network, plan, timeout, await)
}

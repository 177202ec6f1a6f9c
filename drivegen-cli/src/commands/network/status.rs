//! `drivegen network status`: the nodes on the bus (a scan of node ids 1-127), then what their
//! heartbeats and EMCYs say while the manager listens.

use std::time::{Duration, Instant};

use drivebus::canopen::client::scan::{scan, NodeIdentity};
use drivebus::canopen::network::{Network, NodeStatus};
use drivebus::canopen::NodeId;

use super::{stop, StatusArgs};
use crate::connect::{can_backend, DynCan};
use crate::error::CliError;

/// Scans, listens, prints one line per node.
pub fn run(args: StatusArgs) -> Result<(), CliError> {
    let (bus, relay) = can_backend(&args.bus.can, args.bus.settings(&[]))?;
    let mut bus = DynCan(bus);
    let all: Vec<NodeId> = (1..=NodeId::MAX).map(NodeId).collect();
    let found = match scan(&mut bus, &all, args.bus.timeout()) {
        Ok(found) => found,
        Err(cause) => {
            stop(relay);
            return Err(CliError::Io(format!("scan on {}: {cause}", args.bus.can)));
        }
    };
    // The manager listens on the same bus for the heartbeats and EMCYs.
    let network = Network::new(bus);
    let until = Instant::now() + Duration::from_millis(args.listen_ms);
    std::thread::sleep(until.saturating_duration_since(Instant::now()));
    let statuses: Vec<NodeStatus> = found.iter().map(|n| network.status(n.node)).collect();
    drop(network);
    stop(relay);
    if found.is_empty() {
        println!("no node answered on {}", args.bus.can);
    }
    for (node, status) in found.iter().zip(statuses) {
        println!("{}", line(node, &status));
    }
    Ok(())
}

fn line(node: &NodeIdentity, status: &NodeStatus) -> String {
    let hex = |v: Option<u32>| v.map_or("?".to_owned(), |v| format!("{v:#010x}"));
    let state = status
        .state
        .map_or("no heartbeat".to_owned(), |s| format!("{s:?}"));
    let emcy = status.last_emcy.map_or("none".to_owned(), |e| {
        format!("{:04X}h (register {:02X}h)", e.code, e.register.bits())
    });
    format!(
        "node {:3}: device type {:#010x}, vendor-ID {}, product code {}, revision {}, NMT {state}, last EMCY {emcy}",
        node.node.get(),
        node.device_type,
        hex(node.vendor_id),
        hex(node.product_code),
        hex(node.revision),
    )
}

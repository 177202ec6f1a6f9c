//! The CANopen scan: expedited uploads of 1000h and 1018h sub 1-3 to node ids 1-127 at once
//! (`drivebus::canopen::client::scan`), each node matched against the descriptions' `[identity]`
//! vendor-ID, product code and revision range.

use std::time::Duration;

use drivebus::canopen::client::scan::{scan as scan_bus, NodeIdentity};
use drivebus::canopen::NodeId;
use drivegen::ir::Device;

use super::{names, verdict, Answer};
use crate::can::CanSettings;
use crate::connect::{can_backend, DynCan};
use crate::error::CliError;

/// Scans every node id on `backend` and describes each node that answers.
pub fn scan(
    backend: &str,
    settings: CanSettings,
    devices: &[Device],
    timeout: Duration,
) -> Result<Vec<Answer>, CliError> {
    let (bus, relay) = can_backend(backend, settings)?;
    let mut bus = DynCan(bus);
    let nodes: Vec<NodeId> = (1..=NodeId::MAX).map(NodeId).collect();
    let found = scan_bus(&mut bus, &nodes, timeout);
    if let Some(mut child) = relay {
        let _ = child.kill();
        let _ = child.wait();
    }
    let found = found.map_err(|cause| CliError::Io(format!("scan on {backend}: {cause}")))?;
    Ok(found.iter().map(|node| answer(node, devices)).collect())
}

fn answer(node: &NodeIdentity, devices: &[Device]) -> Answer {
    let matches = matching(devices, node);
    let line = format!(
        "node {:3}: device type {:#010x}, vendor-ID {}, product code {}, revision {}: {}",
        node.node.get(),
        node.device_type,
        hex(node.vendor_id),
        hex(node.product_code),
        hex(node.revision),
        verdict(&matches)
    );
    let json = serde_json::json!({
        "node": node.node.get(),
        "device_type": node.device_type,
        "vendor_id": node.vendor_id,
        "product_code": node.product_code,
        "revision": node.revision,
        "matches": names(&matches),
    });
    Answer { line, json }
}

/// The descriptions whose known CANopen identity the node reports.
fn matching<'a>(devices: &'a [Device], node: &NodeIdentity) -> Vec<&'a Device> {
    matching_identity(devices, node.vendor_id, node.product_code, node.revision)
}

/// The descriptions whose `[identity]` covers a node reporting these 1018h entries (also the
/// LSS address `drivegen lss` finds).
pub(crate) fn matching_identity(
    devices: &[Device],
    vendor_id: Option<u32>,
    product_code: Option<u32>,
    revision: Option<u32>,
) -> Vec<&Device> {
    devices
        .iter()
        .filter(|d| {
            d.identity
                .as_ref()
                .is_some_and(|id| id.covers_node(vendor_id, product_code, revision))
        })
        .collect()
}

fn hex(value: Option<u32>) -> String {
    value.map_or("-".into(), |v| format!("{v:#010x}"))
}

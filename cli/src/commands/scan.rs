//! `drivegen scan`: the CANopen nodes on a bus, their identity (1000h, 1018h) and which given
//! description's `[identity]` matches each.

use std::path::PathBuf;
use std::time::Duration;

use drivebus::canopen::scan::{scan, NodeIdentity};
use drivebus::canopen::NodeId;
use drivegen::ir::Device;

use crate::connect::{can_backend, DynCan};
use crate::error::CliError;

/// Arguments of `scan`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// CANopen backend: `slcan:HOST:PORT` or `candump:exec:COMMAND`.
    #[arg(long)]
    can: String,
    /// Descriptions to match the nodes against (repeatable).
    #[arg(long = "description")]
    descriptions: Vec<PathBuf>,
    /// How long to wait for the answers to each object, in milliseconds.
    #[arg(long, default_value_t = 100)]
    timeout_ms: u64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// Scans node ids 1-127 and prints one line (or JSON object) per answering node.
pub fn run(args: Args) -> Result<(), CliError> {
    let devices = args
        .descriptions
        .iter()
        .map(|d| super::load(d))
        .collect::<Result<Vec<_>, _>>()?;
    let (bus, relay) = can_backend(&args.can)?;
    let mut bus = DynCan(bus);
    let nodes: Vec<NodeId> = (1..=NodeId::MAX).map(NodeId).collect();
    let found = scan(&mut bus, &nodes, Duration::from_millis(args.timeout_ms));
    if let Some(mut child) = relay {
        let _ = child.kill();
        let _ = child.wait();
    }
    let found = found.map_err(|cause| CliError::Io(format!("scan on {}: {cause}", args.can)))?;
    for node in &found {
        let matches = matching(&devices, node);
        if args.json {
            println!("{}", to_json(node, &matches));
        } else {
            println!(
                "node {:3}: device type {:#010x}, vendor-ID {}, product code {}, revision {}: {}",
                node.node.get(),
                node.device_type,
                hex(node.vendor_id),
                hex(node.product_code),
                hex(node.revision),
                if matches.is_empty() {
                    "no match".to_string()
                } else {
                    matches.join(", ")
                }
            );
        }
    }
    Ok(())
}

/// Names of the descriptions whose known CANopen identity the node reports.
fn matching(devices: &[Device], node: &NodeIdentity) -> Vec<String> {
    devices
        .iter()
        .filter(|d| {
            d.identity.as_ref().is_some_and(|id| {
                id.vendor_id.is_some()
                    && id.vendor_id == node.vendor_id
                    && id.product_code.is_none_or(|p| Some(p) == node.product_code)
                    && id.revisions.is_none_or(|(min, max)| {
                        node.revision.is_some_and(|r| (min..=max).contains(&r))
                    })
            })
        })
        .map(|d| d.device.name.clone())
        .collect()
}

fn hex(value: Option<u32>) -> String {
    value.map_or("-".into(), |v| format!("{v:#010x}"))
}

fn to_json(node: &NodeIdentity, matches: &[String]) -> serde_json::Value {
    serde_json::json!({
        "node": node.node.get(),
        "device_type": node.device_type,
        "vendor_id": node.vendor_id,
        "product_code": node.product_code,
        "revision": node.revision,
        "matches": matches,
    })
}

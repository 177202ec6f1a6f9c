//! `drivegen network boot`: every node of a network file booted at once over one bus; one line
//! per node.

use drivebus::canopen::network::boot::{boot_node, BootReport};
use drivebus::canopen::network::Network;
use drivebus::canopen::nmt::NmtCommand;
use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::interpret::{self, Variant};

use super::plan::{plan, Planned};
use super::{open, stop, BootArgs};
use crate::connect::DynCan;
use crate::error::CliError;

/// Checks the file against its descriptions, then boots every node.
pub fn run(args: BootArgs) -> Result<(), CliError> {
    let planned = plan(&args.file)?;
    let devices: Vec<_> = planned.iter().map(|p| &p.device).collect();
    let (network, relay) = open(&args.bus, &devices)?;
    let timeout = args.bus.timeout();
    let lines: Vec<(bool, String)> = std::thread::scope(|scope| {
        let running: Vec<_> = planned
            .iter()
            .map(|node| scope.spawn(|| boot(&network, node, timeout)))
            .collect();
        running
            .into_iter()
            .map(|thread| {
                thread
                    .join()
                    .unwrap_or((false, "the boot thread failed".to_owned()))
            })
            .collect()
    });
    drop(network);
    stop(relay);
    for (_, line) in &lines {
        println!("{line}");
    }
    let failed = lines.iter().filter(|(ok, _)| !ok).count();
    match failed {
        0 => Ok(()),
        _ => Err(CliError::Io(format!(
            "{failed} of {} node(s) not booted",
            lines.len()
        ))),
    }
}

/// Boots one node: the procedure (probe, identity, heartbeat), the boot parameters through the
/// interpreter (range and bound checks as `drivegen write` makes them), then NMT Start.
fn boot(
    network: &Network<DynCan>,
    planned: &Planned,
    timeout: std::time::Duration,
) -> (bool, String) {
    let node = NodeId(planned.entry.id);
    let head = format!("node {:3} ({})", node.get(), planned.device.device.name);
    let report: BootReport = boot_node(network, &planned.procedure(), timeout);
    if let Err(why) = report.result {
        return (false, format!("{head}: {why}"));
    }
    let variant = match planned.device.variants.first() {
        Some(first) => Variant::Selected(first.name.clone()),
        None => Variant::Single,
    };
    let mut link = CanOpenLink::new(network.node(node).with_timeout(timeout), node);
    for (name, bytes, line) in &planned.writes {
        let Some(parameter) = planned.parameter(name) else {
            continue;
        };
        if let Err(error) =
            interpret::write_checked(&planned.device, &mut link, &variant, parameter, bytes)
        {
            return (
                false,
                format!("{head}: boot parameter {name} (line {line}) failed: {error}"),
            );
        }
    }
    if planned.entry.start {
        if let Err(error) = network.nmt(NmtCommand::Start, Some(node)) {
            return (false, format!("{head}: NMT start failed: {error}"));
        }
    }
    let started = if planned.entry.start { ", started" } else { "" };
    (
        true,
        format!(
            "{head}: booted, {} parameter(s) written{started}",
            planned.writes.len()
        ),
    )
}

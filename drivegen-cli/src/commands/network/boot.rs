//! `drivegen network boot`: every node of a network file booted at once over one bus; one line
//! per node.

use drivebus::canopen::network::boot::{boot_node, BootError, BootReport, BootStep};
use drivebus::canopen::network::{Network, NodeSdo};
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
    let lines: Vec<(bool, String)> =
        crate::at_once::at_once(&planned, |node| boot(&network, node, timeout))
            .into_iter()
            .map(|done| done.unwrap_or((false, "the boot thread failed".to_owned())))
            .collect();
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

/// Boots one node: the procedure (probe, identity, heartbeat, PDOs, each compared first), the
/// boot parameters through the interpreter (read and compared first; where they differ,
/// written with the range and bound checks `drivegen write` makes), then NMT Start.
fn boot(
    network: &Network<DynCan>,
    planned: &Planned,
    timeout: std::time::Duration,
) -> (bool, String) {
    let node = NodeId(planned.entry.id);
    let head = format!("node {:3} ({})", node.get(), planned.device.device.name);
    let report: BootReport = boot_node(network, &planned.procedure(), timeout);
    if let Err(why) = report.result {
        return (false, format!("{head}: {}", failed_step(planned, &why)));
    }
    let mut link = CanOpenLink::new(network.node(node).with_timeout(timeout), node);
    let (mut written, mut unchanged) = (report.written, report.unchanged);
    for (name, bytes, line) in &planned.writes {
        match boot_parameter(planned, &mut link, name, bytes) {
            Ok(true) => written += 1,
            Ok(false) => unchanged += 1,
            Err(error) => {
                return (
                    false,
                    format!("{head}: boot parameter {name} (line {line}) failed: {error}"),
                )
            }
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
        format!("{head}: booted, {written} written, {unchanged} unchanged{started}"),
    )
}

/// Writes boot parameter `name` unless the node holds `bytes` already; whether it wrote.
fn boot_parameter(
    planned: &Planned,
    link: &mut CanOpenLink<NodeSdo>,
    name: &str,
    bytes: &[u8],
) -> Result<bool, interpret::InterpretError> {
    let Some(parameter) = planned.parameter(name) else {
        return Ok(false);
    };
    let variant = match planned.device.variants.first() {
        Some(first) => Variant::Selected(first.name.clone()),
        None => Variant::Single,
    };
    // A parameter that cannot be read back is written.
    if let Ok(held) = interpret::read_raw(link, &variant, &[parameter]) {
        if held.first().is_some_and(|held| held == bytes) {
            return Ok(false);
        }
    }
    interpret::write_checked(&planned.device, link, &variant, parameter, bytes)?;
    Ok(true)
}

/// Why the procedure stopped, a PDO step named by its table's line.
fn failed_step(planned: &Planned, why: &BootError) -> String {
    match why {
        BootError::Step {
            step: BootStep::Pdo(n),
            error,
        } => {
            let pdo = &planned.pdos[*n];
            let kind = match pdo.kind {
                drivebus::canopen::pdo::PdoKind::Transmit => "TPDO",
                drivebus::canopen::pdo::PdoKind::Receive => "RPDO",
            };
            let line = planned.entry.pdos.get(*n).map_or(0, |p| p.line);
            format!(
                "{kind} {} (line {line}) configuration failed: {error}",
                pdo.number
            )
        }
        other => other.to_string(),
    }
}

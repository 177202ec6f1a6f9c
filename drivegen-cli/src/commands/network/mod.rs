//! `drivegen network`: one CAN bus with many nodes through the network manager
//! (`drivebus::canopen::network`): `boot` boots the nodes a network file lists, `status`
//! lists the nodes on the bus with their identity, NMT state and last EMCY (docs/network.md).

mod boot;
mod plan;
mod status;

use std::path::PathBuf;

use crate::can::CanSettings;
use crate::error::CliError;

/// Arguments of `network`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, clap::Subcommand)]
enum Command {
    /// Boot the nodes a network file lists, all at once: probe, check the identity, set the
    /// heartbeat, write the boot parameters, start. Missing and foreign nodes are reported and
    /// left alone (exit code 1).
    Boot(BootArgs),
    /// The nodes on the bus: identity, NMT state (from their heartbeats) and last EMCY.
    Status(StatusArgs),
}

/// The CAN bus of a `network` command.
#[derive(Debug, clap::Args)]
struct CanArgs {
    /// CANopen backend: `socketcan:IFACE`, `slcan:/dev/PATH` (serial speed --baud, default
    /// 115200), `slcan:HOST:PORT` or `candump:exec:COMMAND`.
    #[arg(long, value_name = "BACKEND")]
    can: String,
    /// --can slcan:...: the CAN bit rate, 10k to 1M (default: the descriptions' documented
    /// default, else 500k).
    #[arg(long, value_name = "BITS", value_parser = crate::can::parse_bitrate)]
    bitrate: Option<u32>,
    /// Serial speed of --can slcan:/dev/PATH.
    #[arg(long)]
    baud: Option<u32>,
    /// How long a node has to answer each request, in milliseconds.
    #[arg(long, default_value_t = 1000)]
    timeout_ms: u64,
}

impl CanArgs {
    fn settings(&self, devices: &[&drivegen::ir::Device]) -> CanSettings {
        CanSettings {
            bitrate: crate::can::bitrate(self.bitrate, devices),
            baud: self.baud.unwrap_or(115_200),
        }
    }

    fn timeout(&self) -> std::time::Duration {
        std::time::Duration::from_millis(self.timeout_ms)
    }
}

/// Arguments of `network boot`.
#[derive(Debug, clap::Args)]
pub struct BootArgs {
    /// The network file (docs/network.md).
    file: PathBuf,
    #[command(flatten)]
    bus: CanArgs,
}

/// Arguments of `network status`.
#[derive(Debug, clap::Args)]
pub struct StatusArgs {
    #[command(flatten)]
    bus: CanArgs,
    /// How long to listen for heartbeats and EMCYs after the scan, in milliseconds.
    #[arg(long, default_value_t = 1500)]
    listen_ms: u64,
}

/// Runs a `network` command.
pub fn run(args: Args) -> Result<(), CliError> {
    match args.command {
        Command::Boot(args) => boot::run(args),
        Command::Status(args) => status::run(args),
    }
}

/// Opens the bus of `args` as a network manager; the relay process, if any, is returned to be
/// stopped.
fn open(
    args: &CanArgs,
    devices: &[&drivegen::ir::Device],
) -> Result<
    (
        drivebus::canopen::network::Network<crate::connect::DynCan>,
        Option<std::process::Child>,
    ),
    CliError,
> {
    let (bus, relay) = crate::connect::can_backend(&args.can, args.settings(devices))?;
    Ok((
        drivebus::canopen::network::Network::new(crate::connect::DynCan(bus)),
        relay,
    ))
}

/// Stops a relay process by its PID.
fn stop(relay: Option<std::process::Child>) {
    if let Some(mut child) = relay {
        let _ = child.kill();
        let _ = child.wait();
    }
}

//! `drivegen lss`: LSS (CiA 305) over any `--can` backend. `scan` finds the nodes that have no
//! node id (Fastscan), shows each with its identity matched against the descriptions as
//! `drivegen scan` does, and with `--assign FIRST` gives them node ids FIRST, FIRST+1, ...;
//! `inquire`, `set-node-id`, `set-bitrate` and `store` address one node by its LSS address
//! (`--address VENDOR:PRODUCT:REVISION:SERIAL`), or the only LSS node on the bus without it.
//! Nothing is stored unless asked (`store`, or `--store`).

mod scan;

use std::path::PathBuf;
use std::time::Duration;

use drivebus::canopen::client::lss::BlockingLss;
use drivebus::canopen::lss::{BitTiming, LssAddress, LssError, LssMode, NewNodeId};
use drivegen::ir::Device;

use crate::can::CanSettings;
use crate::connect::{can_backend, DynCan};
use crate::error::CliError;

/// Arguments of `lss`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    action: Action,
    /// CANopen backend: `socketcan:IFACE`, `slcan:/dev/PATH`, `slcan:HOST:PORT` or
    /// `candump:exec:COMMAND`.
    #[arg(long, value_name = "BACKEND", global = true)]
    can: Option<String>,
    /// --can slcan:...: the CAN bit rate the adapter opens at (default: the descriptions'
    /// documented default, else 500k).
    #[arg(long, value_name = "BITS", value_parser = crate::can::parse_bitrate, global = true)]
    bitrate: Option<u32>,
    /// Serial speed of --can slcan:/dev/PATH (default 115200).
    #[arg(long, global = true)]
    baud: Option<u32>,
    /// The node's LSS address, VENDOR:PRODUCT:REVISION:SERIAL (1018h sub 1-4; hex with 0x);
    /// without it the command goes to every LSS node, and more than one answer is an error.
    #[arg(long, value_name = "V:P:R:S", value_parser = parse_address, global = true)]
    address: Option<LssAddress>,
    /// How long a node has to answer each command, in milliseconds.
    #[arg(long, default_value_t = 500, global = true)]
    timeout_ms: u64,
    /// Descriptions to match identities against (repeatable; default: the shipped ones).
    #[arg(long = "description", global = true)]
    descriptions: Vec<PathBuf>,
}

#[derive(Debug, clap::Subcommand)]
enum Action {
    /// Fastscan: every node without a node id, with its identity; --assign gives them ids.
    Scan(scan::Args),
    /// The node's LSS address (identity) and node id.
    Inquire,
    /// Give the node a node id (1-127, or 255 for none); it takes it at its next reset.
    SetNodeId {
        /// The new node id.
        id: u8,
        /// Store it too, so it survives a power cycle.
        #[arg(long)]
        store: bool,
    },
    /// Give the node a bit rate (10k, 20k, 50k, 100k, 125k, 250k, 500k, 800k, 1M).
    SetBitrate {
        /// The new bit rate.
        #[arg(value_parser = crate::can::parse_bitrate)]
        bits: u32,
        /// Store it too, so it survives a power cycle.
        #[arg(long)]
        store: bool,
        /// Then switch every node to the new bit rate after this many milliseconds.
        #[arg(long, value_name = "MS")]
        activate: Option<u16>,
    },
    /// Store the node's configured node id and bit rate.
    Store,
}

/// Runs the LSS command.
pub fn run(args: Args) -> Result<(), CliError> {
    let backend = args
        .can
        .clone()
        .ok_or_else(|| CliError::Usage("name the bus: --can BACKEND".into()))?;
    // Refused before the bus is opened: nothing is sent.
    match &args.action {
        Action::SetNodeId { id, .. } => {
            NewNodeId::new(*id).map_err(|e| CliError::Usage(e.to_string()))?;
        }
        // --assign gives ids from FIRST up: 255 (none) is not a first id.
        Action::Scan(scan::Args {
            assign: Some(id), ..
        }) if drivebus::canopen::NodeId::new(*id).is_none() => {
            return Err(CliError::Usage(LssError::InvalidNodeId(*id).to_string()));
        }
        Action::SetBitrate { bits, .. } => {
            timing(*bits)?;
        }
        _ => {}
    }
    let devices = devices(&args.descriptions)?;
    let settings = CanSettings {
        bitrate: crate::can::bitrate(args.bitrate, &devices.iter().collect::<Vec<_>>()),
        baud: args.baud.unwrap_or(crate::can::DEFAULT_SLCAN_BAUD),
    };
    let (bus, relay) = can_backend(&backend, settings)?;
    let step = match &args.action {
        Action::Scan(scan) => scan.step(),
        _ => drivebus::canopen::client::lss::DEFAULT_FASTSCAN_STEP,
    };
    let mut lss = BlockingLss::new(DynCan(bus))
        .with_timeout(Duration::from_millis(args.timeout_ms))
        .with_fastscan_step(step);
    let result = act(&args, &mut lss, &devices);
    if let Some(mut child) = relay {
        let _ = child.kill();
        let _ = child.wait();
    }
    result.map_err(|e| CliError::Io(format!("lss on {backend}: {e}")))
}

fn act(args: &Args, lss: &mut BlockingLss<DynCan>, devices: &[Device]) -> Result<(), LssError> {
    if let Action::Scan(scan) = &args.action {
        return scan::run(scan, lss, devices);
    }
    select(lss, args.address)?;
    let result = configure(&args.action, lss, devices);
    // Back to waiting state whatever happened: a node left in configuration state would take
    // the next configure command meant for another.
    let back = lss.switch_global(LssMode::Waiting);
    result.and(back)
}

fn configure(
    action: &Action,
    lss: &mut BlockingLss<DynCan>,
    devices: &[Device],
) -> Result<(), LssError> {
    match action {
        Action::Scan(_) => {}
        Action::Inquire => {
            let address = lss.inquire_address()?;
            let node = lss.inquire_node_id()?;
            println!("{}", scan::describe(&address, Some(node), devices));
        }
        Action::SetNodeId { id, store } => {
            lss.configure_node_id(*id)?;
            if *store {
                lss.store()?;
            }
            let kept = if *store { "stored" } else { "not stored" };
            println!("node id {id} configured ({kept}); the node takes it at its next reset");
        }
        Action::SetBitrate {
            bits,
            store,
            activate,
        } => {
            let timing = timing(*bits).map_err(|_| LssError::NoAnswer)?;
            lss.configure_bit_timing(timing)?;
            if *store {
                lss.store()?;
            }
            if let Some(delay) = activate {
                lss.activate_bit_timing(*delay)?;
            }
            println!("bit rate {bits} bit/s configured");
        }
        Action::Store => {
            lss.store()?;
            println!("configuration stored");
        }
    }
    Ok(())
}

/// Puts the node at `address` (or every LSS node) into configuration state.
fn select(lss: &mut BlockingLss<DynCan>, address: Option<LssAddress>) -> Result<(), LssError> {
    match address {
        Some(address) => lss.switch_selective(address),
        None => lss.switch_global(LssMode::Configuration),
    }
}

/// The CiA 305 table entry for `bits`, or a usage error naming the rates it has.
fn timing(bits: u32) -> Result<BitTiming, CliError> {
    BitTiming::from_bits_per_second(bits).ok_or_else(|| {
        CliError::Usage(format!(
            "{bits} bit/s is not in the CiA 305 bit timing table: 10k, 20k, 50k, 100k, 125k, 250k, 500k, 800k or 1M"
        ))
    })
}

fn devices(paths: &[PathBuf]) -> Result<Vec<Device>, CliError> {
    let paths = if paths.is_empty() {
        super::scan::shipped()?
    } else {
        paths.to_vec()
    };
    paths.iter().map(|p| super::load(p)).collect()
}

/// `VENDOR:PRODUCT:REVISION:SERIAL`, each decimal or 0x-hex.
fn parse_address(text: &str) -> Result<LssAddress, String> {
    let words: Vec<u32> = text
        .split(':')
        .map(|w| {
            let w = w.trim();
            match w.strip_prefix("0x").or_else(|| w.strip_prefix("0X")) {
                Some(hex) => u32::from_str_radix(&hex.replace('_', ""), 16).ok(),
                None => w.parse().ok(),
            }
        })
        .collect::<Option<_>>()
        .ok_or_else(|| format!("{text}: expected VENDOR:PRODUCT:REVISION:SERIAL"))?;
    let words: [u32; 4] = words
        .try_into()
        .map_err(|_| format!("{text}: expected four words, VENDOR:PRODUCT:REVISION:SERIAL"))?;
    Ok(LssAddress::from_words(words))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lss_addresses_take_four_decimal_or_hex_words() {
        assert_eq!(
            parse_address("0x515:2:0x10:42"),
            Ok(LssAddress::from_words([0x515, 2, 0x10, 42]))
        );
        for bad in ["1:2:3", "1:2:3:4:5", "x:1:2:3", ""] {
            assert!(parse_address(bad).is_err(), "{bad}");
        }
    }
}

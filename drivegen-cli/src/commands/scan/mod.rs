//! `drivegen scan`: which drives answer on a bus, who they say they are, and which shipped or
//! given description's `[identity]` covers each. Over CANopen every node id is asked for 1000h
//! and 1018h at once ([`canopen`]); over Modbus every unit id of a range is asked for the
//! identity register of each candidate description ([`modbus`]). A drive no description covers
//! gets a "no match" line; nothing is ever written.

pub(crate) mod canopen;
mod modbus;

use std::path::{Path, PathBuf};
use std::time::Duration;

use drivegen::ir::Device;

use crate::error::CliError;

/// Arguments of `scan`.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("bus").required(true)))]
pub struct Args {
    /// CANopen backend: `socketcan:IFACE` (a Linux kernel CAN interface), `slcan:/dev/PATH` (a
    /// serial SLCAN adapter; serial speed --baud, default 115200), `slcan:HOST:PORT` (SLCAN over
    /// TCP) or `candump:exec:COMMAND`; node ids 1-127 are probed.
    #[arg(long, value_name = "BACKEND", group = "bus")]
    can: Option<String>,
    /// --can slcan:...: the CAN bit rate, 10k to 1M (default: the documented default the
    /// descriptions agree on, else 500k).
    #[arg(long, value_name = "BITS", value_parser = crate::can::parse_bitrate)]
    bitrate: Option<u32>,
    /// Modbus TCP server or gateway, HOST:PORT; the --units are probed over several connections
    /// at once (--connections).
    #[arg(long, value_name = "HOST:PORT", group = "bus")]
    modbus_tcp: Option<String>,
    /// Modbus RTU on a serial port (or pty); the --units are probed one after the other.
    #[arg(long, value_name = "PATH", group = "bus")]
    serial: Option<String>,
    /// Baud rate of --serial (default 19200), or serial speed of --can slcan:/dev/PATH (default
    /// 115200).
    #[arg(long)]
    baud: Option<u32>,
    /// Parity of --serial: none, even or odd.
    #[arg(long, default_value = "even")]
    parity: String,
    /// Stop bits of --serial: 1 or 2.
    #[arg(long, default_value_t = 1)]
    stop_bits: u8,
    /// Modbus unit ids to probe: FIRST-LAST or one id.
    #[arg(long, value_name = "FIRST-LAST", default_value = "1-247")]
    units: String,
    /// Modbus TCP: how many connections probe units at once (1 to 64).
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u8).range(1..=64))]
    connections: u8,
    /// Descriptions to match the drives against (repeatable; default: the shipped ones).
    #[arg(long = "description")]
    descriptions: Vec<PathBuf>,
    /// How long to wait for an answer, in milliseconds (CANopen: for each object, from all
    /// nodes at once; Modbus: for each request).
    #[arg(long, default_value_t = 100)]
    timeout_ms: u64,
    /// Print one JSON object per drive.
    #[arg(long)]
    json: bool,
}

/// One drive that answered: a line for people and a JSON object for scripts.
pub struct Answer {
    /// `node  5: ...` or `unit  3: ...`, ending with the matching descriptions or `no match`.
    line: String,
    /// The same as JSON, with a `matches` list.
    json: serde_json::Value,
}

/// Scans the bus and prints one line (or JSON object) per drive that answers.
pub fn run(args: Args) -> Result<(), CliError> {
    let paths = if args.descriptions.is_empty() {
        shipped()?
    } else {
        args.descriptions.clone()
    };
    let devices = paths
        .iter()
        .map(|d| super::load(d))
        .collect::<Result<Vec<_>, _>>()?;
    let timeout = Duration::from_millis(args.timeout_ms);
    let answers = if let Some(backend) = &args.can {
        let settings = crate::can::CanSettings {
            bitrate: crate::can::bitrate(args.bitrate, &devices.iter().collect::<Vec<_>>()),
            baud: args.baud.unwrap_or(crate::can::DEFAULT_SLCAN_BAUD),
        };
        canopen::scan(backend, settings, &devices, timeout)?
    } else {
        let units = unit_range(&args.units)?;
        let probes = modbus::probes(&devices)?;
        if let Some(addr) = &args.modbus_tcp {
            let connections = usize::from(args.connections);
            modbus::scan_tcp(addr, &units, &probes, timeout, connections)?
        } else if let Some(path) = &args.serial {
            let line =
                crate::connect::serial_config(args.baud, &args.parity, args.stop_bits, timeout)?;
            modbus::scan_rtu(path, &line, &units, &probes)?
        } else {
            return Err(CliError::Usage(
                "name a bus: --can BACKEND, --modbus-tcp HOST:PORT or --serial PATH".into(),
            ));
        }
    };
    for answer in answers {
        if args.json {
            println!("{}", answer.json);
        } else {
            println!("{}", answer.line);
        }
    }
    Ok(())
}

/// The names of the descriptions that cover a drive, or `no match`.
pub(crate) fn verdict(matches: &[&Device]) -> String {
    if matches.is_empty() {
        return "no match".into();
    }
    let names: Vec<&str> = matches.iter().map(|d| d.device.name.as_str()).collect();
    names.join(", ")
}

/// The names of the descriptions that cover a drive, for JSON.
pub(crate) fn names(matches: &[&Device]) -> Vec<String> {
    matches.iter().map(|d| d.device.name.clone()).collect()
}

/// The shipped descriptions: every folder with a device.toml under the source tree's
/// `descriptions/` (profiles are included by them, not drives).
pub(crate) fn shipped() -> Result<Vec<PathBuf>, CliError> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions");
    let entries = std::fs::read_dir(&root).map_err(|e| {
        CliError::Usage(format!(
            "no shipped descriptions at {} ({e}): give --description",
            root.display()
        ))
    })?;
    let mut found: Vec<PathBuf> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.join("device.toml").is_file())
        .collect();
    found.sort();
    Ok(found)
}

/// `FIRST-LAST` (inclusive) or one unit id, within 1..=247 (0 is the broadcast address).
fn unit_range(text: &str) -> Result<Vec<u8>, CliError> {
    let usage = || CliError::Usage(format!("--units {text}: expected FIRST-LAST within 1-247"));
    let id = |t: &str| {
        t.trim()
            .parse::<u8>()
            .ok()
            .filter(|id| (1..=247).contains(id))
            .ok_or_else(usage)
    };
    let (first, last) = match text.split_once('-') {
        Some((first, last)) => (id(first)?, id(last)?),
        None => (id(text)?, id(text)?),
    };
    if first > last {
        return Err(usage());
    }
    Ok((first..=last).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_ranges_are_inclusive_and_stay_within_1_to_247() {
        assert_eq!(unit_range("3-5").unwrap(), [3, 4, 5]);
        assert_eq!(unit_range("7").unwrap(), [7]);
        assert_eq!(unit_range("1-247").unwrap().len(), 247);
        for bad in ["0-3", "5-3", "1-248", "x", ""] {
            assert!(matches!(unit_range(bad), Err(CliError::Usage(_))), "{bad}");
        }
    }

    #[test]
    fn the_shipped_descriptions_are_the_drive_folders() {
        let names: Vec<String> = shipped()
            .unwrap()
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert!(names.contains(&"lafert-smartris".to_string()), "{names:?}");
        assert!(!names.contains(&"profiles".to_string()), "{names:?}");
    }
}

//! `drivegen sim`: serve a simulated drive until interrupted, or several drives on one bus (one
//! per unit id or node id, each with its own state), as a scan or a multi-drive master sees them.

use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::{CanBus, CanFrame, NodeId};
use drivebus::modbus::client::{SerialConfig, SerialStream};
use drivebus::modbus::UnitId;
use drivebus::rs232::client::{open_line, Rs232Config, DEFAULT_BAUD};
use drivebus::rs232::{LoopMode, StationId};
use drivegen::ir::Device;
use drivesim::canopen::{nodes, Node, NodeConfig};
use drivesim::modbus::tcp::TcpServer;
use drivesim::modbus::Units;
use drivesim::Simulator;

use crate::can::{self, CanSettings, CanSpec};
use crate::connect::DynCan;
use crate::error::CliError;

/// Arguments of `sim`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Description file, or a folder with a device.toml; several serve several drives on one
    /// bus, paired in order with the --unit or --node-id values (one description and several ids:
    /// the same drive at each id).
    #[arg(required = true)]
    descriptions: Vec<PathBuf>,
    /// Serve Modbus TCP on HOST:PORT (port 0: a free port, printed).
    #[arg(long, value_name = "HOST:PORT", group = "bus")]
    modbus_tcp: Option<String>,
    /// Serve Modbus RTU on a serial port or pty.
    #[arg(long, value_name = "PATH", group = "bus")]
    serial: Option<String>,
    /// Be one or several CANopen nodes: `socketcan:IFACE` (a Linux kernel CAN interface, e.g.
    /// vcan0), `slcan:/dev/PATH` (a serial SLCAN adapter; serial speed --baud, default
    /// 115200), `slcan:HOST:PORT` (connects to an SLCAN gateway) or `candump:stdio` (frames as
    /// candump lines on stdin/stdout; the `listening on` line goes to stderr).
    #[arg(long, value_name = "BACKEND", group = "bus")]
    can: Option<String>,
    /// --can slcan:...: the CAN bit rate, 10k, 20k, 50k, 100k, 125k, 250k, 500k, 800k or 1M
    /// (default: the description's documented default, else 500k).
    #[arg(long, value_name = "BITS", value_parser = crate::can::parse_bitrate)]
    bitrate: Option<u32>,
    /// Serve the Kinco RS-232 protocol on a serial port or pty (8N1), station --node-id, from
    /// the parameters' `rs232` addresses.
    #[arg(long, value_name = "PATH", group = "bus")]
    kinco_rs232: Option<String>,
    /// --kinco-rs232: be a drive in a multi-point loop (RS232_Loop_Enable = 1), repeating every
    /// telegram before answering.
    #[arg(long)]
    rs232_loop: bool,
    /// Baud rate of --serial (default 19200) or --kinco-rs232 (default 38400), or serial speed
    /// of --can slcan:/dev/PATH (default 115200).
    #[arg(long)]
    baud: Option<u32>,
    /// Modbus unit id (default 1); repeat it to serve several drives on one port.
    #[arg(long)]
    unit: Vec<u8>,
    /// CANopen node id, or Kinco RS-232 station id (default: the description's CANopen node id,
    /// else 1 on RS-232); repeat it to put several nodes on one CAN bus.
    #[arg(long)]
    node_id: Vec<u8>,
    /// --can: start every node without a node id (LSS "not configured"), silent until an LSS
    /// master (`drivegen lss scan --assign`) gives it one; the drives must be LSS slaves. The
    /// --node-id values then only tell the drives apart (for --set, e.g. a serial_number each).
    #[arg(long)]
    lss_unconfigured: bool,
    /// Heartbeat period in ms when the description has no 1017h (0: none).
    #[arg(long, default_value_t = 0)]
    heartbeat_ms: u64,
    /// Preset a parameter to a raw value at start, e.g. --set operation_mode=2 (repeatable);
    /// `--set 5:vendor_id=0x1234` presets it only in the drive at unit / node id 5.
    #[arg(long, value_name = "[ID:]NAME=RAW")]
    set: Vec<String>,
}

/// One simulated drive and the unit / node id it answers at.
struct Drive {
    id: u8,
    device: Device,
    sim: Simulator,
}

/// Starts the simulator and serves until interrupted (or, on candump stdio, until stdin ends).
pub fn run(args: Args) -> Result<(), CliError> {
    let drives = drives(&args)?;
    for preset in &args.set {
        apply(preset, &drives)?;
    }
    if let Some(addr) = &args.modbus_tcp {
        let units = Units::new(drives.iter().map(|d| (UnitId(d.id), d.sim.clone())));
        let server = TcpServer::gateway(units, addr.as_str())
            .map_err(|e| CliError::Io(format!("cannot listen on {addr}: {e}")))?;
        announce(&format!(
            "listening on modbus-tcp {} unit {}",
            server.local_addr(),
            ids(&drives)
        ));
        server.join();
        return Ok(());
    }
    if let Some(path) = &args.serial {
        let mut stream = SerialStream::open(path, &SerialConfig::new(args.baud.unwrap_or(19_200)))
            .map_err(|e| CliError::Io(format!("cannot open {path}: {e}")))?;
        announce(&format!(
            "listening on modbus-rtu {path} unit {}",
            ids(&drives)
        ));
        let units = Units::new(drives.iter().map(|d| (UnitId(d.id), d.sim.clone())));
        return drivesim::modbus::rtu::serve_units(&units, &mut stream)
            .map_err(|e| CliError::Io(format!("{path}: {e}")));
    }
    if let Some(backend) = &args.can {
        let devices: Vec<&Device> = drives.iter().map(|d| &d.device).collect();
        let settings = CanSettings {
            bitrate: can::bitrate(args.bitrate, &devices),
            baud: args.baud.unwrap_or(can::DEFAULT_SLCAN_BAUD),
        };
        let mut nodes = drives
            .iter()
            .map(|d| {
                let node = NodeId::new(d.id).ok_or_else(|| {
                    CliError::Usage(format!("node id {}: expected 1..=127", d.id))
                })?;
                crate::connect::warn_node_relative_defaults(&d.device, d.id);
                let config = NodeConfig {
                    node,
                    heartbeat: (args.heartbeat_ms > 0)
                        .then(|| Duration::from_millis(args.heartbeat_ms)),
                };
                let node = Node::new(d.sim.clone(), config, d.sim.variant())
                    .lss_bit_rate(settings.bitrate);
                if !args.lss_unconfigured {
                    return Ok(node);
                }
                if node.lss().is_none() {
                    return Err(CliError::Usage(format!(
                        "--lss-unconfigured: {} is not an LSS slave (its description has no `[canopen] lss`)",
                        d.device.device.name
                    )));
                }
                Ok(node.lss_unconfigured())
            })
            .collect::<Result<Vec<_>, CliError>>()?;
        return run_can(&mut nodes, backend, settings, &ids(&drives));
    }
    if let Some(path) = &args.kinco_rs232 {
        let [drive] = drives.as_slice() else {
            return Err(CliError::Usage(
                "--kinco-rs232 serves one drive: give one description and one --node-id".into(),
            ));
        };
        return serve_rs232(&drive.sim, &args, drive.id, path);
    }
    Err(CliError::Usage(
        "name a bus: --modbus-tcp HOST:PORT, --serial PATH, --can BACKEND or --kinco-rs232 PATH"
            .into(),
    ))
}

/// The drives to serve: each description paired with its id (or one description at every id).
fn drives(args: &Args) -> Result<Vec<Drive>, CliError> {
    let devices = args
        .descriptions
        .iter()
        .map(|d| super::load(d))
        .collect::<Result<Vec<_>, _>>()?;
    let given = if args.modbus_tcp.is_some() || args.serial.is_some() {
        &args.unit
    } else {
        &args.node_id
    };
    let ids: Vec<u8> = match (devices.len(), given.len()) {
        (_, 0) => devices.iter().map(|d| default_id(args, d)).collect(),
        (1, _) => given.clone(),
        (n, m) if n == m => given.clone(),
        (n, m) => {
            return Err(CliError::Usage(format!(
                "{n} descriptions and {m} ids: give one id per description"
            )))
        }
    };
    let mut drives = Vec::new();
    for (i, id) in ids.into_iter().enumerate() {
        let device = devices[i.min(devices.len() - 1)].clone();
        if drives.iter().any(|d: &Drive| d.id == id) {
            return Err(CliError::Usage(format!(
                "two drives at id {id}: give each description its own --unit / --node-id"
            )));
        }
        let sim = Simulator::new(device.clone());
        drives.push(Drive { id, device, sim });
    }
    Ok(drives)
}

/// The id a drive answers at when none is given: unit 1 on Modbus, else the description's
/// CANopen node id, else 1.
fn default_id(args: &Args, device: &Device) -> u8 {
    if args.modbus_tcp.is_some() || args.serial.is_some() {
        return 1;
    }
    device.canopen.as_ref().map_or(1, |c| c.default_node_id)
}

/// Applies one `--set [ID:]NAME=RAW` to the drive at ID, or to every drive.
fn apply(preset: &str, drives: &[Drive]) -> Result<(), CliError> {
    let usage = || CliError::Usage(format!("--set {preset}: expected [ID:]NAME=RAW"));
    let (target, raw) = preset.split_once('=').ok_or_else(usage)?;
    let raw = parse_raw(raw).ok_or_else(usage)?;
    let (id, name) = match target.split_once(':') {
        Some((id, name)) => (Some(id.parse::<u8>().map_err(|_| usage())?), name),
        None => (None, target),
    };
    let mut targets = drives
        .iter()
        .filter(|d| id.is_none_or(|id| d.id == id))
        .peekable();
    if targets.peek().is_none() {
        return Err(CliError::Usage(format!(
            "--set {preset}: no drive at that id"
        )));
    }
    for drive in targets {
        super::parameter(&drive.device, name)?;
        drive
            .sim
            .preset(name, raw)
            .map_err(|e| CliError::Usage(e.to_string()))?;
    }
    Ok(())
}

/// The ids, comma-separated, for the announcement.
fn ids(drives: &[Drive]) -> String {
    let ids: Vec<String> = drives.iter().map(|d| d.id.to_string()).collect();
    ids.join(",")
}

fn serve_rs232(sim: &Simulator, args: &Args, station: u8, path: &str) -> Result<(), CliError> {
    let mode = if args.rs232_loop {
        LoopMode::MultiPoint
    } else {
        LoopMode::PointToPoint
    };
    let line = Rs232Config {
        baud: args.baud.unwrap_or(DEFAULT_BAUD),
        ..Rs232Config::default()
    };
    let mut stream =
        open_line(path, &line).map_err(|e| CliError::Io(format!("cannot open {path}: {e}")))?;
    let mut server = sim.rs232_server(StationId(station), mode);
    announce(&format!(
        "listening on kinco-rs232 {path} station {station}"
    ));
    drivesim::rs232::serve(&mut server, &mut stream)
        .map_err(|e| CliError::Io(format!("{path}: {e}")))
}

/// The forms `sim --can` takes.
const SIM_FORMS: &str = "socketcan:IFACE, slcan:/dev/PATH, slcan:HOST:PORT or candump:stdio";

fn run_can(
    nodes: &mut [Node],
    backend: &str,
    settings: CanSettings,
    ids: &str,
) -> Result<(), CliError> {
    let ended = |e| CliError::Io(format!("{backend}: {e}"));
    let spec = CanSpec::parse(backend, SIM_FORMS)?;
    match spec {
        CanSpec::CandumpStdio => {
            // stdout carries the frames: the announcement goes to stderr.
            eprintln!("listening on canopen candump:stdio node {ids}");
            let mut bus = CandumpBus::new(std::io::stdin(), std::io::stdout());
            match nodes::run(nodes, &mut bus) {
                Err(drivebus::BusError::Io(std::io::ErrorKind::UnexpectedEof)) => Ok(()),
                other => other.map_err(ended),
            }
        }
        CanSpec::CandumpExec(_) => Err(CliError::Usage(format!(
            "--can {backend}: expected {SIM_FORMS}"
        ))),
        spec => {
            let (bus, _) = can::open(backend, &spec, settings)?;
            let mut bus = RidesOutBusOff(DynCan(bus));
            announce(&format!("listening on canopen {backend} node {ids}"));
            nodes::run(nodes, &mut bus).map_err(ended)
        }
    }
}

/// A simulated node rides out a bus-off as a drive does (it is reported, the node waits for
/// the controller's restart) instead of ending the simulation.
struct RidesOutBusOff(DynCan);

impl CanBus for RidesOutBusOff {
    fn send(&mut self, frame: &CanFrame) -> Result<(), drivebus::BusError> {
        match self.0.send(frame) {
            Err(drivebus::BusError::CanQueueFull) => {
                eprintln!("sim: transmit queue full, frame dropped");
                Ok(())
            }
            other => other,
        }
    }
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, drivebus::BusError> {
        match self.0.recv(timeout) {
            Err(drivebus::BusError::CanBusOff) => {
                eprintln!("sim: the CAN controller reported bus-off");
                Ok(None)
            }
            other => other,
        }
    }
}

fn parse_raw(text: &str) -> Option<i128> {
    match text.strip_prefix("0x") {
        Some(hex) => i128::from_str_radix(hex, 16).ok(),
        None => text.parse().ok(),
    }
}

fn announce(line: &str) {
    println!("{line}");
    let _ = std::io::stdout().flush();
}

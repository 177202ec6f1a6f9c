//! `drivegen sim`: serve a simulated drive until interrupted.

use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

use drivebus::canopen::backend::candump::CandumpBus;
use drivebus::canopen::backend::slcan::{Bitrate, SlcanBus};
use drivebus::canopen::NodeId;
use drivebus::modbus::transport::{SerialConfig, SerialStream};
use drivebus::modbus::UnitId;
use drivebus::rs232::serial::{open_line, Rs232Config, DEFAULT_BAUD};
use drivebus::rs232::{LoopMode, StationId};
use drivegen::ir::Device;
use drivesim::canopen::{Node, NodeConfig};
use drivesim::Simulator;

use crate::error::CliError;

/// Arguments of `sim`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
    /// Serve Modbus TCP on HOST:PORT (port 0: a free port, printed).
    #[arg(long, value_name = "HOST:PORT", group = "bus")]
    modbus_tcp: Option<String>,
    /// Serve Modbus RTU on a serial port or pty.
    #[arg(long, value_name = "PATH", group = "bus")]
    serial: Option<String>,
    /// Be a CANopen node: `candump:stdio` (frames as candump lines on stdin/stdout; the
    /// `listening on` line goes to stderr) or `slcan:HOST:PORT` (connects to an SLCAN gateway).
    #[arg(long, value_name = "BACKEND", group = "bus")]
    can: Option<String>,
    /// Serve the Kinco RS-232 protocol on a serial port or pty (8N1), station --node-id, from
    /// the parameters' `rs232` addresses.
    #[arg(long, value_name = "PATH", group = "bus")]
    kinco_rs232: Option<String>,
    /// --kinco-rs232: be a drive in a multi-point loop (RS232_Loop_Enable = 1), repeating every
    /// telegram before answering.
    #[arg(long)]
    rs232_loop: bool,
    /// Baud rate of --serial (default 19200) or --kinco-rs232 (default 38400).
    #[arg(long)]
    baud: Option<u32>,
    /// Modbus unit id.
    #[arg(long, default_value_t = 1)]
    unit: u8,
    /// CANopen node id, or Kinco RS-232 station id (default: the description's CANopen node id,
    /// else 1 on RS-232).
    #[arg(long)]
    node_id: Option<u8>,
    /// Heartbeat period in ms when the description has no 1017h (0: none).
    #[arg(long, default_value_t = 0)]
    heartbeat_ms: u64,
    /// Preset a parameter to a raw value at start, e.g. --set operation_mode=2 (repeatable).
    #[arg(long, value_name = "NAME=RAW")]
    set: Vec<String>,
}

/// Starts the simulator and serves until interrupted (or, on candump stdio, until stdin ends).
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    let sim = Simulator::new(device.clone());
    for preset in &args.set {
        let (name, raw) = preset
            .split_once('=')
            .and_then(|(n, r)| Some((n, parse_raw(r)?)))
            .ok_or_else(|| CliError::Usage(format!("--set {preset}: expected NAME=RAW")))?;
        super::parameter(&device, name)?;
        sim.preset(name, raw)
            .map_err(|e| CliError::Usage(e.to_string()))?;
    }
    if let Some(addr) = &args.modbus_tcp {
        let server = sim
            .serve_modbus_tcp(addr.as_str(), UnitId(args.unit))
            .map_err(|e| CliError::Io(format!("cannot listen on {addr}: {e}")))?;
        announce(&format!(
            "listening on modbus-tcp {} unit {}",
            server.local_addr(),
            args.unit
        ));
        server.join();
        return Ok(());
    }
    if let Some(path) = &args.serial {
        let mut stream = SerialStream::open(path, &SerialConfig::new(args.baud.unwrap_or(19_200)))
            .map_err(|e| CliError::Io(format!("cannot open {path}: {e}")))?;
        announce(&format!(
            "listening on modbus-rtu {path} unit {}",
            args.unit
        ));
        return drivesim::modbus::rtu::serve(&sim, &mut stream, UnitId(args.unit))
            .map_err(|e| CliError::Io(format!("{path}: {e}")));
    }
    if let Some(backend) = &args.can {
        let node = args
            .node_id
            .or(device.canopen.as_ref().map(|c| c.default_node_id))
            .and_then(NodeId::new)
            .ok_or_else(|| CliError::Usage("give a CANopen --node-id (1..=127)".into()))?;
        let config = NodeConfig {
            node,
            heartbeat: (args.heartbeat_ms > 0).then(|| Duration::from_millis(args.heartbeat_ms)),
        };
        let mut node_sim = Node::new(sim.clone(), config, sim.variant());
        return run_can(&mut node_sim, backend, node);
    }
    if let Some(path) = &args.kinco_rs232 {
        return serve_rs232(&sim, &args, &device, path);
    }
    Err(CliError::Usage(
        "name a bus: --modbus-tcp HOST:PORT, --serial PATH, --can BACKEND or --kinco-rs232 PATH"
            .into(),
    ))
}

fn serve_rs232(sim: &Simulator, args: &Args, device: &Device, path: &str) -> Result<(), CliError> {
    let station = args
        .node_id
        .or(device.canopen.as_ref().map(|c| c.default_node_id))
        .unwrap_or(1);
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

fn run_can(node_sim: &mut Node, backend: &str, node: NodeId) -> Result<(), CliError> {
    let ended = |e| CliError::Io(format!("{backend}: {e}"));
    if backend == "candump:stdio" {
        // stdout carries the frames: the announcement goes to stderr.
        eprintln!("listening on canopen candump:stdio node {}", node.0);
        let mut bus = CandumpBus::new(std::io::stdin(), std::io::stdout());
        return match node_sim.run(&mut bus) {
            Err(drivebus::BusError::Io(std::io::ErrorKind::UnexpectedEof)) => Ok(()),
            other => other.map_err(ended),
        };
    }
    if let Some(addr) = backend.strip_prefix("slcan:") {
        let mut bus = SlcanBus::connect(addr).map_err(ended)?;
        bus.open(Bitrate::K500).map_err(ended)?;
        announce(&format!("listening on canopen {backend} node {}", node.0));
        return node_sim.run(&mut bus).map_err(ended);
    }
    Err(CliError::Usage(format!(
        "--can {backend}: expected candump:stdio or slcan:HOST:PORT"
    )))
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

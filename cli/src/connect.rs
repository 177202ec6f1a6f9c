//! Reaching a drive from the command line: the bus options every talking subcommand shares,
//! and a [`Session`] that reads and writes parameters by their IR addresses.

use std::process::Child;
use std::time::Duration;

use clap::Args;
use drivebus::canopen::blocking::BlockingSdo;
use drivebus::canopen::{CanBus, CanFrame, CanOpenLink, NodeId};
use drivebus::interpret::{self, InterpretError};
use drivebus::modbus::rtu::{Parity, StopBits};
use drivebus::modbus::transport::SerialStream;
use drivebus::modbus::transport::{ModbusTcpClient, SerialConfig, SerialRtuClient, TcpConfig};
use drivebus::modbus::{ModbusLimits, ModbusLink, RegisterBus, UnitId, MAX_IN_FLIGHT};
use drivebus::rs232::serial::{Rs232Client, Rs232Config, DEFAULT_BAUD};
use drivebus::rs232::{LoopMode, Rs232Link, StationId};
use drivebus::BusError;
use drivegen::ir::{Device, Parameter};

use crate::can::{self, CanSettings};
use crate::error::CliError;
use crate::modbus_limits;

/// How to reach the drive.
#[derive(Debug, Args, Clone)]
pub struct BusArgs {
    /// Modbus TCP server, HOST:PORT.
    #[arg(long, value_name = "HOST:PORT", group = "bus")]
    pub modbus_tcp: Option<String>,
    /// Modbus RTU on a serial port (or pty).
    #[arg(long, value_name = "PATH", group = "bus")]
    pub serial: Option<String>,
    /// CANopen over CAN: `socketcan:IFACE` (a Linux kernel CAN interface, e.g. can0 or vcan0),
    /// `slcan:/dev/PATH` (a serial SLCAN adapter such as a CANable, e.g. /dev/ttyACM0; serial
    /// speed --baud, default 115200), `slcan:HOST:PORT` (SLCAN over TCP) or
    /// `candump:exec:COMMAND` (a process that speaks candump lines on its stdio, e.g. a relay or
    /// `drivegen sim ... --can candump:stdio`).
    #[arg(long, value_name = "BACKEND", group = "bus")]
    pub can: Option<String>,
    /// --can slcan:...: the CAN bit rate the adapter is set to, 10k, 20k, 50k, 100k, 125k, 250k,
    /// 500k, 800k or 1M (default: the description's documented default, else 500k). A SocketCAN
    /// interface has its bit rate set by `ip link`.
    #[arg(long, value_name = "BITS", value_parser = crate::can::parse_bitrate)]
    pub bitrate: Option<u32>,
    /// The Kinco RS-232 protocol on a serial port (or pty), 8N1; the station id is --node-id.
    /// A Kinco FD's RS-485 port speaks it too, out of the box (6510h sub 0Ch = 1).
    #[arg(long, value_name = "PATH", group = "bus")]
    pub kinco_rs232: Option<String>,
    /// --kinco-rs232: the drives are wired in a multi-point loop (RS232_Loop_Enable = 1), so
    /// each request comes back before its answer.
    #[arg(long)]
    pub rs232_loop: bool,
    /// Baud rate of --serial (default 19200) or --kinco-rs232 (default 38400, the drive's
    /// factory setting).
    #[arg(long)]
    pub baud: Option<u32>,
    /// Parity of --serial: none, even or odd.
    #[arg(long, default_value = "even")]
    pub parity: String,
    /// Stop bits of --serial: 1 or 2.
    #[arg(long, default_value_t = 1)]
    pub stop_bits: u8,
    /// Modbus unit id.
    #[arg(long, default_value_t = 1)]
    pub unit: u8,
    /// CANopen node id, or Kinco RS-232 station id (default: the description's CANopen node id,
    /// else 1 on RS-232).
    #[arg(long)]
    pub node_id: Option<u8>,
    /// How long the drive has to answer, in milliseconds.
    #[arg(long, default_value_t = 1000)]
    pub timeout_ms: u64,
    /// Modbus TCP: how many read requests may await their answers at once (1 to 16). Above 1,
    /// the requests for several parameters go out together; the server must read its
    /// connection request by request.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=MAX_IN_FLIGHT as i64))]
    pub max_in_flight: u8,
}

/// A CAN backend behind a box.
/// A boxed CAN backend as a [`CanBus`].
pub struct DynCan(pub Box<dyn CanBus + Send>);

impl CanBus for DynCan {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.0.send(frame)
    }
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        self.0.recv(timeout)
    }
}

enum Link {
    Modbus {
        bus: Box<dyn RegisterBus + Send>,
        unit: UnitId,
        /// The described limits: registers per read, and whether FC 0x10 exists (without it
        /// values are written word by word).
        limits: ModbusLimits,
    },
    CanOpen {
        sdo: BlockingSdo<DynCan>,
        node: NodeId,
    },
    Rs232 {
        bus: Rs232Client<SerialStream>,
        station: StationId,
    },
}

/// A connection to one drive described by `device`.
pub struct Session {
    link: Link,
    target: String,
    relay: Option<Child>,
}

impl Drop for Session {
    fn drop(&mut self) {
        if let Some(child) = &mut self.relay {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

fn parity(text: &str) -> Result<Parity, CliError> {
    match text {
        "none" => Ok(Parity::None),
        "even" => Ok(Parity::Even),
        "odd" => Ok(Parity::Odd),
        other => Err(CliError::Usage(format!(
            "--parity {other}: expected none, even or odd"
        ))),
    }
}

fn connect_error(target: &str, e: BusError) -> CliError {
    CliError::Io(format!("cannot open {target}: {e}"))
}

impl Session {
    /// Opens the bus the options name.
    pub fn open(args: &BusArgs, device: &Device) -> Result<Self, CliError> {
        let timeout = Duration::from_millis(args.timeout_ms);
        if let Some(addr) = &args.modbus_tcp {
            let config = TcpConfig {
                timeout,
                connect_timeout: timeout,
                max_in_flight: args.max_in_flight.into(),
                ..TcpConfig::default()
            };
            let target = format!("Modbus TCP {addr} unit {}", args.unit);
            let bus = ModbusTcpClient::connect(addr.as_str(), &config)
                .map_err(|e| connect_error(&target, e))?;
            return Ok(Self::modbus(Box::new(bus), args.unit, device, target));
        }
        if let Some(path) = &args.serial {
            let config = serial_config(args.baud, &args.parity, args.stop_bits, timeout)?;
            let target = format!("Modbus RTU {path} unit {}", args.unit);
            let bus =
                SerialRtuClient::open(path, &config).map_err(|e| connect_error(&target, e))?;
            return Ok(Self::modbus(Box::new(bus), args.unit, device, target));
        }
        if let Some(backend) = &args.can {
            let node = args
                .node_id
                .or(device.canopen.as_ref().map(|c| c.default_node_id))
                .and_then(NodeId::new)
                .ok_or_else(|| CliError::Usage("give a CANopen --node-id (1..=127)".into()))?;
            let settings = CanSettings {
                bitrate: can::bitrate(args.bitrate, &[device]),
                baud: args.baud.unwrap_or(can::DEFAULT_SLCAN_BAUD),
            };
            let (bus, relay) = can_backend(backend, settings)?;
            return Ok(Self {
                link: Link::CanOpen {
                    sdo: BlockingSdo::new(DynCan(bus)).with_timeout(timeout),
                    node,
                },
                target: format!("CANopen {backend} node {}", node.0),
                relay,
            });
        }
        if let Some(path) = &args.kinco_rs232 {
            return Self::rs232(args, device, path, timeout);
        }
        Err(CliError::Usage(
            "name a bus: --modbus-tcp HOST:PORT, --serial PATH, --can BACKEND or --kinco-rs232 PATH"
                .into(),
        ))
    }

    fn rs232(
        args: &BusArgs,
        device: &Device,
        path: &str,
        timeout: Duration,
    ) -> Result<Self, CliError> {
        let config = Rs232Config {
            baud: args.baud.unwrap_or(DEFAULT_BAUD),
            timeout,
            mode: if args.rs232_loop {
                LoopMode::MultiPoint
            } else {
                LoopMode::PointToPoint
            },
        };
        let station = StationId(station_id(args, device));
        let target = format!("Kinco RS-232 {path} station {}", station.0);
        let bus = Rs232Client::open(path, config).map_err(|e| connect_error(&target, e))?;
        Ok(Self {
            link: Link::Rs232 { bus, station },
            target,
            relay: None,
        })
    }

    fn modbus(bus: Box<dyn RegisterBus + Send>, unit: u8, device: &Device, target: String) -> Self {
        Self {
            link: Link::Modbus {
                bus,
                unit: UnitId(unit),
                limits: modbus_limits::limits(device),
            },
            target,
            relay: None,
        }
    }

    /// Whether the bus reaches `parameter` for reading (it has a readable address on this
    /// protocol).
    pub fn can_read(&self, parameter: &Parameter) -> bool {
        match self.link {
            Link::Modbus { .. } => parameter.readable_over_modbus(),
            Link::CanOpen { .. } => parameter.readable_over_canopen(),
            Link::Rs232 { .. } => parameter.readable_over_rs232(),
        }
    }

    /// Where the drive is, for messages.
    pub fn target(&self) -> &str {
        &self.target
    }

    /// Reads the raw bytes of each parameter through the run-time interpreter: over Modbus with
    /// the fewest requests the device's limits allow (sent together with `--max-in-flight`),
    /// over CANopen and RS-232 an upload each.
    pub fn read_many(&mut self, parameters: &[&Parameter]) -> Result<Vec<Vec<u8>>, CliError> {
        let read = match &mut self.link {
            Link::Modbus { bus, unit, limits } => {
                return read_modbus(&mut **bus, *unit, *limits, &self.target, parameters);
            }
            Link::CanOpen { sdo, node } => {
                interpret::read_raw(&mut CanOpenLink::new(sdo, *node), parameters)
            }
            Link::Rs232 { bus, station } => {
                interpret::read_raw(&mut Rs232Link::new(bus, *station), parameters)
            }
        };
        read.map_err(|e| interpret_error(&self.target, e))
    }

    /// Writes the raw bytes of `parameter` through the run-time interpreter, after checking them
    /// against the current values of the parameters that bound it.
    pub fn write(
        &mut self,
        device: &Device,
        parameter: &Parameter,
        bytes: &[u8],
    ) -> Result<(), CliError> {
        let written = match &mut self.link {
            Link::Modbus { bus, unit, limits } => checked_write(
                device,
                &mut ModbusLink::new(&mut **bus, *unit, *limits),
                parameter,
                bytes,
            ),
            Link::CanOpen { sdo, node } => {
                checked_write(device, &mut CanOpenLink::new(sdo, *node), parameter, bytes)
            }
            Link::Rs232 { bus, station } => {
                checked_write(device, &mut Rs232Link::new(bus, *station), parameter, bytes)
            }
        };
        written.map_err(|e| interpret_error(&self.target, e))
    }
}

/// The bound check, then the write, over one link.
fn checked_write<L>(
    device: &Device,
    link: &mut L,
    parameter: &Parameter,
    bytes: &[u8],
) -> Result<(), InterpretError>
where
    L: drivebus::Link,
    Parameter: interpret::Addressed<L::Protocol>,
{
    interpret::check_bounds(device, link, parameter, bytes)?;
    interpret::write_raw(link, parameter, bytes)
}

/// A failure of the interpreter reaching `target`, as the CLI reports it.
fn interpret_error(target: &str, error: InterpretError) -> CliError {
    match error {
        InterpretError::Bus { parameter, cause } => CliError::Bus {
            target: target.to_owned(),
            parameter,
            cause,
        },
        InterpretError::NoAccess { .. } => CliError::NoAccess(error.to_string()),
        InterpretError::OutsideBound { .. } => CliError::OutsideBound(error.to_string()),
        InterpretError::UnknownParameter(_) | InterpretError::Input { .. } => {
            CliError::Usage(error.to_string())
        }
    }
}

/// Reads the raw bytes of each parameter from `unit` through the run-time interpreter, with the
/// fewest requests `limits` allow; a failure names the parameter and `target`.
pub fn read_modbus(
    bus: &mut dyn RegisterBus,
    unit: UnitId,
    limits: ModbusLimits,
    target: &str,
    parameters: &[&Parameter],
) -> Result<Vec<Vec<u8>>, CliError> {
    interpret::read_raw(&mut ModbusLink::new(bus, unit, limits), parameters)
        .map_err(|e| interpret_error(target, e))
}

/// The serial line settings of `--baud` (default 19200), `--parity` and `--stop-bits`.
pub fn serial_config(
    baud: Option<u32>,
    parity_name: &str,
    stop_bits: u8,
    timeout: Duration,
) -> Result<SerialConfig, CliError> {
    Ok(SerialConfig {
        parity: parity(parity_name)?,
        stop_bits: if stop_bits == 2 {
            StopBits::Two
        } else {
            StopBits::One
        },
        timeout,
        ..SerialConfig::new(baud.unwrap_or(19_200))
    })
}

/// Opens the CAN backend `spec` names (one of [`can::FORMS`]); a relay process is returned for
/// the session to stop.
pub fn can_backend(
    spec: &str,
    settings: CanSettings,
) -> Result<(Box<dyn CanBus + Send>, Option<Child>), CliError> {
    let parsed = can::CanSpec::parse(spec, can::FORMS)?;
    can::open(spec, &parsed, settings)
}

/// The RS-232 station: --node-id, else the description's CANopen node id (the drive's one id,
/// manual line 2183), else 1.
fn station_id(args: &BusArgs, device: &Device) -> u8 {
    args.node_id
        .or(device.canopen.as_ref().map(|c| c.default_node_id))
        .unwrap_or(1)
}

//! Reaching a drive from the command line: the bus options every talking subcommand shares,
//! and a [`Session`] that reads and writes parameters by their IR addresses.

use std::process::{Child, Command, Stdio};
use std::time::Duration;

use clap::Args;
use drivebus::canopen::backend::candump::CandumpBus;
use drivebus::canopen::backend::slcan::{Bitrate, SlcanBus};
use drivebus::canopen::blocking::BlockingSdo;
use drivebus::canopen::{CanBus, CanFrame, NodeId, SdoBus};
use drivebus::interpret::registers;
use drivebus::modbus::rtu::{Parity, StopBits};
use drivebus::modbus::transport::{ModbusTcpClient, SerialConfig, SerialRtuClient, TcpConfig};
use drivebus::modbus::{ModbusLimits, RegisterBus, UnitId, MAX_IN_FLIGHT};
use drivebus::BusError;
use drivegen::ir::{self, Device, Parameter};

use crate::error::CliError;
use crate::modbus_batch;

/// How to reach the drive.
#[derive(Debug, Args, Clone)]
pub struct BusArgs {
    /// Modbus TCP server, HOST:PORT.
    #[arg(long, value_name = "HOST:PORT", group = "bus")]
    pub modbus_tcp: Option<String>,
    /// Modbus RTU on a serial port (or pty).
    #[arg(long, value_name = "PATH", group = "bus")]
    pub serial: Option<String>,
    /// CANopen: `slcan:HOST:PORT` (SLCAN over TCP) or `candump:exec:COMMAND` (a process that
    /// speaks candump lines on its stdio, e.g. a relay or `drivegen sim ... --can candump:stdio`).
    #[arg(long, value_name = "BACKEND", group = "bus")]
    pub can: Option<String>,
    /// Baud rate of --serial.
    #[arg(long, default_value_t = 19_200)]
    pub baud: u32,
    /// Parity of --serial: none, even or odd.
    #[arg(long, default_value = "even")]
    pub parity: String,
    /// Stop bits of --serial: 1 or 2.
    #[arg(long, default_value_t = 1)]
    pub stop_bits: u8,
    /// Modbus unit id.
    #[arg(long, default_value_t = 1)]
    pub unit: u8,
    /// CANopen node id (default: the description's).
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
struct DynCan(Box<dyn CanBus + Send>);

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
            let config = SerialConfig {
                parity: parity(&args.parity)?,
                stop_bits: if args.stop_bits == 2 {
                    StopBits::Two
                } else {
                    StopBits::One
                },
                timeout,
                ..SerialConfig::new(args.baud)
            };
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
            let (bus, relay) = can_backend(backend)?;
            return Ok(Self {
                link: Link::CanOpen {
                    sdo: BlockingSdo::new(DynCan(bus)).with_timeout(timeout),
                    node,
                },
                target: format!("CANopen {backend} node {}", node.0),
                relay,
            });
        }
        Err(CliError::Usage(
            "name a bus: --modbus-tcp HOST:PORT, --serial PATH or --can BACKEND".into(),
        ))
    }

    fn modbus(bus: Box<dyn RegisterBus + Send>, unit: u8, device: &Device, target: String) -> Self {
        Self {
            link: Link::Modbus {
                bus,
                unit: UnitId(unit),
                limits: modbus_batch::limits(device),
            },
            target,
            relay: None,
        }
    }

    /// Where the drive is, for messages.
    pub fn target(&self) -> &str {
        &self.target
    }

    /// Reads the raw bytes of each parameter: over Modbus with the fewest requests the device's
    /// limits allow (sent together with `--max-in-flight`), over CANopen an SDO upload each.
    pub fn read_many(&mut self, parameters: &[&Parameter]) -> Result<Vec<Vec<u8>>, CliError> {
        let target = &self.target;
        match &mut self.link {
            Link::CanOpen { sdo, node } => parameters
                .iter()
                .map(|p| {
                    let address = object_address(p, true)?;
                    upload(sdo, *node, p, address).map_err(|e| bus_error(target, p, e))
                })
                .collect(),
            Link::Modbus { bus, unit, limits } => {
                let wire = parameters
                    .iter()
                    .map(|p| modbus_address(p, true).map(|a| a.wire))
                    .collect::<Result<Vec<_>, _>>()?;
                let values = modbus_batch::read_wire(&mut **bus, *unit, *limits, &wire).map_err(
                    |failure| bus_error(target, parameters[failure.value], failure.cause),
                )?;
                parameters
                    .iter()
                    .zip(values)
                    .map(|(parameter, wire)| {
                        registers::from_wire(parameter.data_type, wire).map_err(|_| {
                            let why = "the registers hold a value outside the parameter's type";
                            bus_error(target, parameter, BusError::Frame(why))
                        })
                    })
                    .collect()
            }
        }
    }

    /// Writes the raw bytes of `parameter`.
    pub fn write(&mut self, parameter: &Parameter, bytes: &[u8]) -> Result<(), CliError> {
        let result = match &mut self.link {
            Link::Modbus { bus, unit, limits } => {
                let address = modbus_address(parameter, false)?;
                let regs = registers::to_registers(
                    parameter.data_type,
                    bytes,
                    address.words,
                    address.word_order,
                );
                if regs.len() > 1 && limits.write_multiple {
                    bus.write_registers(*unit, address.address, &regs)
                } else {
                    // FC 0x06 per word, in address order.
                    (0..).zip(&regs).try_for_each(|(i, &word)| {
                        bus.write_register(*unit, address.address.wrapping_add(i), word)
                    })
                }
            }
            Link::CanOpen { sdo, node } => {
                let address = object_address(parameter, false)?;
                sdo.download(*node, address.index, address.subindex, bytes)
            }
        };
        result.map_err(|e| bus_error(&self.target, parameter, e))
    }
}

/// Opens a CAN backend; a relay process is returned for the session to stop.
fn can_backend(spec: &str) -> Result<(Box<dyn CanBus + Send>, Option<Child>), CliError> {
    if let Some(addr) = spec.strip_prefix("slcan:") {
        let mut bus = SlcanBus::connect(addr).map_err(|e| connect_error(spec, e))?;
        bus.open(Bitrate::K500)
            .map_err(|e| connect_error(spec, e))?;
        return Ok((Box::new(bus), None));
    }
    if let Some(command) = spec.strip_prefix("candump:exec:") {
        let mut words = command.split_whitespace();
        let program = words
            .next()
            .ok_or_else(|| CliError::Usage("candump:exec: needs a command".into()))?;
        let mut child = Command::new(program)
            .args(words)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .map_err(|e| CliError::Io(format!("cannot start `{command}`: {e}")))?;
        let bus = CandumpBus::from_child(&mut child).map_err(|e| connect_error(spec, e))?;
        return Ok((Box::new(bus), Some(child)));
    }
    Err(CliError::Usage(format!(
        "--can {spec}: expected slcan:HOST:PORT or candump:exec:COMMAND"
    )))
}

/// A bus failure reaching `target`, naming the parameter it was for.
fn bus_error(target: &str, parameter: &Parameter, cause: BusError) -> CliError {
    CliError::Bus {
        target: target.to_owned(),
        parameter: parameter.name.clone(),
        cause,
    }
}

/// The value of `parameter` at `address`, by SDO upload.
fn upload(
    sdo: &mut BlockingSdo<DynCan>,
    node: NodeId,
    parameter: &Parameter,
    address: &ir::ObjectAddress,
) -> Result<Vec<u8>, BusError> {
    let mut buf = vec![0u8; (parameter.data_type.bytes() as usize).max(8)];
    sdo.upload(node, address.index, address.subindex, &mut buf)
        .map(|len| buf[..len].to_vec())
}

fn no_access(parameter: &Parameter, protocol: &str, read: bool) -> CliError {
    let (verb, what) = if read {
        ("read", "write-only")
    } else {
        ("written", "read-only")
    };
    CliError::NoAccess(format!(
        "{} cannot be {verb} over {protocol} (it is {what} there, or has no {protocol} address)",
        parameter.name
    ))
}

fn modbus_address(parameter: &Parameter, read: bool) -> Result<&ir::ModbusAddress, CliError> {
    parameter
        .modbus
        .iter()
        .find(|a| if read { a.access.read } else { a.access.write })
        .ok_or_else(|| no_access(parameter, "Modbus", read))
}

fn object_address(parameter: &Parameter, read: bool) -> Result<&ir::ObjectAddress, CliError> {
    parameter
        .canopen
        .iter()
        .find(|a| if read { a.access.read } else { a.access.write })
        .ok_or_else(|| no_access(parameter, "CANopen", read))
}

//! Reaching a drive from the command line: the bus options every talking subcommand shares,
//! and a [`Session`] that reads and writes parameters by their IR addresses.

use std::process::Child;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::Duration;

use clap::Args;
use drivebus::canopen::{CanBus, CanFrame, CanOpenLink, NodeId};
use drivebus::interpret::{self, InterpretError, Variant};
use drivebus::modbus::client::SerialStream;
use drivebus::modbus::client::{ModbusTcpClient, SerialConfig, SerialRtuClient, TcpConfig};
use drivebus::modbus::rtu::{Parity, StopBits};
use drivebus::modbus::{ModbusLimits, ModbusLine, ModbusLink, RegisterBus, UnitId, MAX_IN_FLIGHT};
use drivebus::rs232::client::{Rs232Client, Rs232Config, DEFAULT_BAUD};
use drivebus::rs232::{LoopMode, Rs232Link, StationId};
use drivebus::BusError;
use drivegen::ir::{Device, Parameter};

use crate::can::{self, CanSettings};
use crate::can_sdo::CanSdo;
use crate::error::CliError;
use drivebus::canopen::client::BlockingSdo;

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
    /// Modbus unit id (default 1). `read` and `watch` take it repeated, for several drives on
    /// one line or gateway: a column each.
    #[arg(long)]
    pub unit: Vec<u8>,
    /// CANopen node id, or Kinco RS-232 station id (default: the description's CANopen node id,
    /// else 1 on RS-232). `read` and `watch` take it repeated, for several nodes on one bus: a
    /// column each.
    #[arg(long)]
    pub node_id: Vec<u8>,
    /// How long the drive has to answer, in milliseconds.
    #[arg(long, default_value_t = 1000)]
    pub timeout_ms: u64,
    /// Modbus TCP: how many read requests may await their answers at once (1 to 16). Above 1,
    /// the requests for several parameters go out together; the server must read its
    /// connection request by request.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=MAX_IN_FLIGHT as i64))]
    pub max_in_flight: u8,
    /// The description's variant (firmware or configuration) the drive is in, instead of the
    /// one it reports (the description's `selected_by` parameter, read when the session opens).
    #[arg(long, value_name = "NAME")]
    pub variant: Option<String>,
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

/// A shared handle on a bus that talks to one drive at a time (a CAN SDO client, an RS-232
/// line): each session's request holds it for its whole exchange.
type Shared<T> = Arc<Mutex<T>>;

/// The CAN bus of CANopen sessions: SDO transfers and, beside them, every other frame.
pub type SharedCan = Shared<BlockingSdo<DynCan>>;

/// Holds a shared bus for one exchange.
pub fn hold<T>(shared: &Shared<T>) -> MutexGuard<'_, T> {
    // Each exchange completes or fails inside one call: a panicked holder left nothing half-sent.
    shared.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The connection a session talks over; sessions for several drives on one bus hold clones.
#[derive(Clone)]
enum Link<'d> {
    Modbus {
        bus: ModbusLine<Box<dyn RegisterBus + Send>>,
        unit: UnitId,
        /// The described limits: registers per read, and whether FC 0x10 exists (without it
        /// values are written word by word).
        limits: ModbusLimits<'d>,
    },
    CanOpen {
        sdo: CanSdo,
        node: NodeId,
    },
    Rs232 {
        bus: Shared<Rs232Client<SerialStream>>,
        station: StationId,
    },
}

/// A relay process the CAN backend runs through, stopped when the last session ends.
struct Relay(Child);

impl Drop for Relay {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A connection to one drive described by `device`, in the variant it reports.
pub struct Session<'d> {
    link: Link<'d>,
    /// The bus, for messages: `Modbus TCP 127.0.0.1:502`.
    place: String,
    /// The bus and the drive on it, for messages: `Modbus TCP 127.0.0.1:502 unit 3`.
    target: String,
    relay: Option<Arc<Relay>>,
    variant: Variant,
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

impl<'d> Session<'d> {
    /// Opens the bus the options name and learns the drive's variant: `--variant`, else the
    /// one the description's `selected_by` parameter reports (as the generated handle's
    /// `detect_variant` does), else, where the drive reports none, the description's default
    /// (its first). A drive that reports a variant the description does not cover still opens:
    /// parameters whose address depends on the variant are then refused, and so is every write
    /// but a stop. The options name one drive: a repeated `--unit` or `--node-id` is refused.
    pub fn open(args: &BusArgs, device: &'d Device) -> Result<Self, CliError> {
        let ids = drive_ids(args, device)?;
        if let [_, _, ..] = ids.as_slice() {
            return Err(CliError::Usage(
                "this command talks to one drive: give --unit or --node-id once (read and watch take several)"
                    .into(),
            ));
        }
        let mut sessions = Self::open_each(args, device)?;
        Ok(sessions.remove(0))
    }

    /// Opens the bus the options name once, and a session for each drive on it that `--unit`
    /// (Modbus) or `--node-id` (CANopen, RS-232) names, in order, each in the variant it
    /// reports (see [`open`](Self::open)). The sessions share the connection: each request
    /// holds it for its exchange.
    pub fn open_each(args: &BusArgs, device: &'d Device) -> Result<Vec<Self>, CliError> {
        Self::open_sharing(args, device, true)
    }

    /// [`open_each`](Self::open_each), the CANopen nodes all on one SDO client with the bus
    /// itself at hand ([`can`](Self::can)), never through a network manager: for `watch --pdo`,
    /// which sends SYNCs and NMT and takes TPDOs beside the transfers.
    pub fn open_each_on_one_client(
        args: &BusArgs,
        device: &'d Device,
    ) -> Result<Vec<Self>, CliError> {
        Self::open_sharing(args, device, false)
    }

    /// The sessions, several CANopen nodes through a network manager when `concurrent`.
    fn open_sharing(
        args: &BusArgs,
        device: &'d Device,
        concurrent: bool,
    ) -> Result<Vec<Self>, CliError> {
        let ids = drive_ids(args, device)?;
        let first = Self::connect(args, device, ids[0], concurrent && ids.len() > 1)?;
        let mut sessions = ids
            .iter()
            .map(|&id| first.to(id, device))
            .collect::<Result<Vec<_>, _>>()?;
        let named = args.variant.as_deref();
        let variants = each(&mut sessions, |session| {
            session.detect_variant(named, device)
        });
        for (session, variant) in sessions.iter_mut().zip(variants) {
            session.variant = variant?;
        }
        Ok(sessions)
    }

    /// Opens the bus `args` names, talking to the drive they name, for sessions to several
    /// drives on it, each with its own description ([`beside`](Self::beside)): the `gateway`'s
    /// drives sharing a serial line or a CAN bus. CANopen nodes go through a network manager
    /// when `several`. The session's variant is not learned: it is the bus, not a drive's.
    pub fn open_line(args: &BusArgs, device: &'d Device, several: bool) -> Result<Self, CliError> {
        Self::connect(args, device, drive_id(args, device)?, several)
    }

    /// A session on this session's connection to the drive `args` names (its `--unit` or
    /// `--node-id`, its `--variant`), described by `device`, in the variant it reports; the
    /// rest of `args` (the bus and its settings) is this connection's.
    pub fn beside(&self, args: &BusArgs, device: &'d Device) -> Result<Self, CliError> {
        let mut session = self.reach(drive_id(args, device)?, device)?;
        session.variant = session.detect_variant(args.variant.as_deref(), device)?;
        Ok(session)
    }

    /// A session on the same connection, to the drive at `id` (unit, node or station).
    fn to(&self, id: u8, device: &'d Device) -> Result<Self, CliError> {
        if matches!(self.link, Link::CanOpen { .. }) {
            warn_node_relative_defaults(device, id);
        }
        self.reach(id, device)
    }

    /// [`to`](Self::to) without the warnings: the gateway reaches a drive again after each
    /// failure, and warns once when it loads.
    fn reach(&self, id: u8, device: &'d Device) -> Result<Self, CliError> {
        let link = match &self.link {
            Link::Modbus { bus, .. } => Link::Modbus {
                bus: bus.clone(),
                unit: UnitId(id),
                limits: device.modbus_limits(),
            },
            Link::CanOpen { sdo, .. } => {
                let node = node_id(id)?;
                Link::CanOpen {
                    sdo: sdo.to(node),
                    node,
                }
            }
            Link::Rs232 { bus, .. } => Link::Rs232 {
                bus: Arc::clone(bus),
                station: StationId(id),
            },
        };
        Ok(Self {
            target: target(&self.place, &link),
            place: self.place.clone(),
            link,
            relay: self.relay.clone(),
            variant: Variant::Single,
        })
    }

    /// The variant named by `--variant`, else the one the drive reports.
    fn detect_variant(
        &mut self,
        named: Option<&str>,
        device: &Device,
    ) -> Result<Variant, CliError> {
        if device.variants.is_empty() {
            return match named {
                None => Ok(Variant::Single),
                Some(name) => Err(CliError::Usage(format!(
                    "--variant {name}: the description has no variants"
                ))),
            };
        }
        if let Some(name) = named {
            return match device.variants.iter().any(|v| v.name == name) {
                true => Ok(Variant::Selected(name.to_owned())),
                false => Err(CliError::Usage(format!(
                    "--variant {name}: the description's variants are {}",
                    device
                        .variants
                        .iter()
                        .map(|v| v.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ))),
            };
        }
        let Some((selector, values)) = device.variant_selection() else {
            // The drive does not report its variant: the description's default, as the
            // generated handle opens in (its first `[[variant]]`).
            return Ok(Variant::Selected(device.variants[0].name.clone()));
        };
        let unknown = |found| Variant::Unknown {
            selector: selector.name.clone(),
            found,
        };
        if !self.can_read(selector) {
            return Ok(unknown(None));
        }
        // A selector the drive does not answer leaves the variant unknown: a stop still goes out.
        let Ok(mut read) = self.read_many(&[selector]) else {
            return Ok(unknown(None));
        };
        let bytes = read.pop().unwrap_or_default();
        let Some(found) = interpret::raw::to_int(selector.data_type, &bytes) else {
            return Ok(unknown(None));
        };
        let selected = values.iter().find(|(_, value)| i128::from(*value) == found);
        Ok(match selected {
            Some((i, _)) => Variant::Selected(device.variants[*i].name.clone()),
            None => unknown(Some(found)),
        })
    }

    /// The variant the session reads and writes in, for messages (empty for a description
    /// without variants).
    pub fn variant_note(&self) -> String {
        match &self.variant {
            Variant::Single => String::new(),
            Variant::Selected(name) => format!(" (variant {name})"),
            Variant::Unknown { .. } => " (variant unknown)".into(),
        }
    }

    /// Opens the bus the options name, talking to the drive at `id`.
    fn connect(
        args: &BusArgs,
        device: &'d Device,
        id: u8,
        several: bool,
    ) -> Result<Self, CliError> {
        let timeout = Duration::from_millis(args.timeout_ms);
        if let Some(addr) = &args.modbus_tcp {
            let config = TcpConfig {
                timeout,
                connect_timeout: timeout,
                max_in_flight: args.max_in_flight.into(),
                ..TcpConfig::default()
            };
            let place = format!("Modbus TCP {addr}");
            let bus = ModbusTcpClient::connect(addr.as_str(), &config)
                .map_err(|e| connect_error(&format!("{place} unit {id}"), e))?;
            return Ok(Self::modbus(Box::new(bus), id, device, place));
        }
        if let Some(path) = &args.serial {
            let config = serial_config(args.baud, &args.parity, args.stop_bits, timeout)?;
            let place = format!("Modbus RTU {path}");
            let bus = SerialRtuClient::open(path, &config)
                .map_err(|e| connect_error(&format!("{place} unit {id}"), e))?;
            return Ok(Self::modbus(Box::new(bus), id, device, place));
        }
        if let Some(backend) = &args.can {
            // Each node's session warns of its node-relative defaults (`to`).
            let node = node_id(id)?;
            let settings = CanSettings {
                bitrate: can::bitrate(args.bitrate, &[device]),
                baud: args.baud.unwrap_or(can::DEFAULT_SLCAN_BAUD),
            };
            let (bus, relay) = can_backend(backend, settings)?;
            let sdo = CanSdo::open(DynCan(bus), node, timeout, several);
            return Ok(Self::new(
                Link::CanOpen { sdo, node },
                format!("CANopen {backend}"),
                relay.map(|child| Arc::new(Relay(child))),
            ));
        }
        if let Some(path) = &args.kinco_rs232 {
            return Self::rs232(args, path, timeout, id);
        }
        Err(CliError::Usage(
            "name a bus: --modbus-tcp HOST:PORT, --serial PATH, --can BACKEND or --kinco-rs232 PATH"
                .into(),
        ))
    }

    fn rs232(args: &BusArgs, path: &str, timeout: Duration, id: u8) -> Result<Self, CliError> {
        let config = Rs232Config {
            baud: args.baud.unwrap_or(DEFAULT_BAUD),
            timeout,
            mode: if args.rs232_loop {
                LoopMode::MultiPoint
            } else {
                LoopMode::PointToPoint
            },
        };
        let place = format!("Kinco RS-232 {path}");
        let bus = Rs232Client::open(path, config)
            .map_err(|e| connect_error(&format!("{place} station {id}"), e))?;
        let link = Link::Rs232 {
            bus: Arc::new(Mutex::new(bus)),
            station: StationId(id),
        };
        Ok(Self::new(link, place, None))
    }

    fn modbus(
        bus: Box<dyn RegisterBus + Send>,
        unit: u8,
        device: &'d Device,
        place: String,
    ) -> Self {
        let link = Link::Modbus {
            bus: ModbusLine::new(bus),
            unit: UnitId(unit),
            limits: device.modbus_limits(),
        };
        Self::new(link, place, None)
    }

    /// A session over `link`, whose bus is at `place`, its variant not learned yet.
    fn new(link: Link<'d>, place: String, relay: Option<Arc<Relay>>) -> Self {
        Self {
            target: target(&place, &link),
            place,
            link,
            relay,
            variant: Variant::Single,
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

    /// Whether the bus reaches `parameter` for writing (it has a writable address on this
    /// protocol).
    pub fn can_write(&self, parameter: &Parameter) -> bool {
        match self.link {
            Link::Modbus { .. } => parameter.modbus.iter().any(|a| a.access.write),
            Link::CanOpen { .. } => parameter.canopen.iter().any(|a| a.access.write),
            Link::Rs232 { .. } => parameter.rs232.iter().any(|a| a.access.write),
        }
    }

    /// The protocol the session speaks, for messages.
    pub fn protocol(&self) -> &'static str {
        match self.link {
            Link::Modbus { .. } => "Modbus",
            Link::CanOpen { .. } => "CANopen",
            Link::Rs232 { .. } => "Kinco RS-232",
        }
    }

    /// Whether this session's requests may run beside other drives' (CANopen nodes through
    /// the network manager).
    pub fn concurrent(&self) -> bool {
        matches!(&self.link, Link::CanOpen { sdo, .. } if sdo.concurrent())
    }

    /// The variant the session reads and writes in.
    pub fn variant(&self) -> &Variant {
        &self.variant
    }

    /// Where the drive is, for messages.
    pub fn target(&self) -> &str {
        &self.target
    }

    /// Which drive on the bus this is: `("unit", 3)`, `("node", 3)` or `("station", 3)`.
    pub fn drive(&self) -> (&'static str, u8) {
        self.link.drive()
    }

    /// The CAN bus and the node of a CANopen session (`watch --pdo` sends SYNC and takes TPDOs
    /// on it); `None` on another protocol, or when the bus is a network manager's (see
    /// [`open_each_on_one_client`](Self::open_each_on_one_client)).
    pub fn can(&self) -> Option<(SharedCan, NodeId)> {
        match &self.link {
            Link::CanOpen {
                sdo: CanSdo::Alone(sdo),
                node,
            } => Some((Arc::clone(sdo), *node)),
            _ => None,
        }
    }

    /// Reads the raw bytes of each parameter through the run-time interpreter: over Modbus with
    /// the fewest requests the device's limits allow (sent together with `--max-in-flight`),
    /// over CANopen and RS-232 an upload each.
    pub fn read_many(&mut self, parameters: &[&Parameter]) -> Result<Vec<Vec<u8>>, CliError> {
        let variant = &self.variant;
        let read = match &mut self.link {
            Link::Modbus { bus, unit, limits } => interpret::read_raw(
                &mut ModbusLink::new(bus, *unit, *limits),
                variant,
                parameters,
            ),
            Link::CanOpen { sdo, node } => sdo.with(|sdo| {
                interpret::read_raw(&mut CanOpenLink::new(sdo, *node), variant, parameters)
            }),
            Link::Rs232 { bus, station } => interpret::read_raw(
                &mut Rs232Link::new(&mut *hold(bus), *station),
                variant,
                parameters,
            ),
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
        let variant = &self.variant;
        let written = match &mut self.link {
            Link::Modbus { bus, unit, limits } => interpret::write_checked(
                device,
                &mut ModbusLink::new(bus, *unit, *limits),
                variant,
                parameter,
                bytes,
            ),
            Link::CanOpen { sdo, node } => sdo.with(|sdo| {
                let mut link = CanOpenLink::new(sdo, *node);
                interpret::write_checked(device, &mut link, variant, parameter, bytes)
            }),
            Link::Rs232 { bus, station } => interpret::write_checked(
                device,
                &mut Rs232Link::new(&mut *hold(bus), *station),
                variant,
                parameter,
                bytes,
            ),
        };
        written.map_err(|e| interpret_error(&self.target, e))
    }
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
        InterpretError::NotInVariant { .. } | InterpretError::VariantUnknown { .. } => {
            CliError::Variant(error.to_string())
        }
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
    limits: ModbusLimits<'_>,
    target: &str,
    variant: &Variant,
    parameters: &[&Parameter],
) -> Result<Vec<Vec<u8>>, CliError> {
    interpret::read_raw(&mut ModbusLink::new(bus, unit, limits), variant, parameters)
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

/// Warns on stderr, once per parameter, when the description's own limits refuse a node-relative
/// default (`$NODEID+0x180`) on node `node`: a vendor EDS whose limits allow node IDs 1..=15 only
/// describes a drive not meant for node 16. Nothing is refused (other tools talk to such a node
/// too); a write is still checked against the limits before anything is sent.
pub fn warn_node_relative_defaults(device: &Device, node: u8) {
    for line in node_relative_default_warnings(device, node) {
        // One write a line: a simulator relay started by this process shares its stderr and
        // warns at the same time, and `eprintln!` writes the line and its break apart.
        let _ = std::io::Write::write_all(&mut std::io::stderr(), format!("{line}\n").as_bytes());
    }
}

/// The lines [`warn_node_relative_defaults`] prints.
fn node_relative_default_warnings(device: &Device, node: u8) -> Vec<String> {
    device
        .defaults_refusing_node(node)
        .into_iter()
        .map(|(p, ids)| {
            let value = p.default_on(node).map_or_else(String::new, |v| format!(", {v},"));
            format!(
                "warning: on node {node} the default of `{}`{value} is outside what the description allows for it; it allows node IDs {ids} only",
                p.name
            )
        })
        .collect()
}

/// The drives the options name on their bus, in order: `--unit` on Modbus (default 1),
/// `--node-id` on CAN (default: the description's node id) and RS-232 (default: the
/// description's CANopen node id, the drive's one id, manual line 2183, else 1). The same id
/// twice is refused.
fn drive_ids(args: &BusArgs, device: &Device) -> Result<Vec<u8>, CliError> {
    let described = device.canopen.as_ref().map(|c| c.default_node_id);
    let (ids, option) = if args.modbus_tcp.is_some() || args.serial.is_some() {
        (non_empty(&args.unit, Some(1)), "--unit")
    } else if args.can.is_some() {
        (non_empty(&args.node_id, described), "--node-id")
    } else {
        (non_empty(&args.node_id, described.or(Some(1))), "--node-id")
    };
    if ids.is_empty() {
        return Err(CliError::Usage("give a CANopen --node-id (1..=127)".into()));
    }
    if let Some(twice) = ids
        .iter()
        .find(|id| ids.iter().filter(|i| i == id).count() > 1)
    {
        return Err(CliError::Usage(format!("{option} {twice} is given twice")));
    }
    Ok(ids)
}

/// The one drive the options name on their bus (the first `--unit` or `--node-id`, else the
/// default as [`drive_ids`] has it).
pub fn drive_id(args: &BusArgs, device: &Device) -> Result<u8, CliError> {
    Ok(drive_ids(args, device)?[0])
}

/// `given`, else `default` alone (if any).
fn non_empty(given: &[u8], default: Option<u8>) -> Vec<u8> {
    match given {
        [] => default.into_iter().collect(),
        ids => ids.to_vec(),
    }
}

/// A CANopen node id, 1..=127.
fn node_id(id: u8) -> Result<NodeId, CliError> {
    NodeId::new(id).ok_or_else(|| CliError::Usage("give a CANopen --node-id (1..=127)".into()))
}

/// `work` done for every session: at once, a thread each, where the sessions are
/// [`concurrent`](Session::concurrent), else one after the other. The results in order.
pub fn each<'d, R: Send>(
    sessions: &mut [Session<'d>],
    work: impl Fn(&mut Session<'d>) -> R + Sync,
) -> Vec<R> {
    if !sessions.iter().all(Session::concurrent) {
        return sessions.iter_mut().map(work).collect();
    }
    crate::at_once::at_once(sessions.iter_mut(), work)
        .into_iter()
        .map(|done| done.unwrap_or_else(|panic| std::panic::resume_unwind(panic)))
        .collect()
}

/// The bus at `place` and the drive `link` talks to, for messages.
fn target(place: &str, link: &Link<'_>) -> String {
    let (kind, id) = link.drive();
    format!("{place} {kind} {id}")
}

impl Link<'_> {
    /// Which drive the link talks to: `("unit", 3)`, `("node", 3)` or `("station", 3)`.
    fn drive(&self) -> (&'static str, u8) {
        match self {
            Link::Modbus { unit, .. } => ("unit", unit.0),
            Link::CanOpen { node, .. } => ("node", node.0),
            Link::Rs232 { station, .. } => ("station", station.0),
        }
    }
}

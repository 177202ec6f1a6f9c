//! The generated crate against an independent Modbus RTU implementation: pymodbus 3.16.1 playing
//! an smd drive (tests/peers/smd_server.py: one register per read except the documented blocks,
//! write-only registers, the unlock and lock rules) on a socat pty pair, reached with drivebus'
//! serial RTU client, in each parameter configuration. Each test starts its peers and stops them
//! by PID. A missing peer fails the test; `tests/peers/setup.sh` at the workspace root installs it.

use std::path::Path;
use std::time::Duration;

use drivebus::modbus::client::{SerialConfig, SerialRtuClient};
use drivebus::modbus::rtu::{Parity, StopBits};
use drivebus::modbus::{ModbusLink, RegisterBus, Table, UnitId};
use drivebus::units::Hertz;
use lenze_smd::types::{OperationalStatus, SerialBaudRate};
use lenze_smd::{Command, LenzeSmd, SmdError, Variant, VariantSelection};
use peer_support::{pty_pair, ready_peer, Process, PtyPair};

const UNIT: UnitId = UnitId(10);
/// The peer's count of accepted writes (its instrumentation, not a drive register).
const ACCEPTED_WRITES: u16 = 200;

type Drive = LenzeSmd<ModbusLink<SerialRtuClient>>;

/// The pty pair and the pymodbus drive on its server end, serving `configuration` as #50.
struct Peer {
    _server: Process,
    pty: PtyPair,
}

fn start(configuration: u16) -> Peer {
    let pty = pty_pair();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/peers/smd_server.py");
    let server = ready_peer(
        &script,
        &[pty.server.to_str().unwrap(), &configuration.to_string()],
    );
    Peer {
        _server: server,
        pty,
    }
}

fn open(peer: &Peer) -> (Drive, VariantSelection) {
    // 9600 baud, 8N2: the smd default (section 2.3 A, line 210).
    let line = SerialConfig {
        parity: Parity::None,
        stop_bits: StopBits::Two,
        timeout: Duration::from_secs(1),
        ..SerialConfig::new(9_600)
    };
    let client = SerialRtuClient::open(peer.pty.client.to_str().unwrap(), &line).unwrap();
    LenzeSmd::open(client, UNIT).unwrap()
}

fn accepted_writes(drive: &mut Drive) -> u16 {
    let mut count = [0u16; 1];
    let link = drive.device().link_mut();
    let unit = link.unit();
    link.bus_mut()
        .read_registers(unit, Table::Holding, ACCEPTED_WRITES, &mut count)
        .unwrap();
    count[0]
}

#[test]
fn pc507_status_version_and_a_control_session() {
    let peer = start(507);
    let (mut drive, selection) = open(&peer);
    assert_eq!(selection, VariantSelection::Known(Variant::Pc507));
    assert_eq!(drive.drive_family().read().map(|f| f.raw()), Ok(69));
    assert_eq!(
        drive.software_version().read().unwrap().as_str(),
        Some("SMD 2.01")
    );
    let status = drive.status().unwrap(); // 6 words at #24, which the peer allows
    assert_eq!(status.command_speed, Hertz(51.3));
    assert_eq!(status.load_and_status.load(), 100);
    assert_eq!(
        status.load_and_status.operational_status(),
        OperationalStatus::RUN
    );
    // c25 is #103 in PC507; the peer's #95 is C99.
    assert_eq!(
        drive.serial_baud_rate().read(),
        Ok(SerialBaudRate::N82_9600)
    );

    let mut session = drive.unlock_controls().unwrap();
    session.command(Command::SerialSpeedReference).unwrap();
    session.serial_speed_command().write(Hertz(41.2)).unwrap();
    assert!(matches!(
        session
            .serial_speed_command()
            .write(Hertz(50.1))
            .map_err(SmdError::from),
        Err(SmdError::OutsideBound(drivebus::OutsideBound {
            bound: "maximum_output_frequency",
            ..
        }))
    ));
    session.command(Command::Start).unwrap();
    session.command(Command::Stop).unwrap();
    session.lock().unwrap();
    assert_eq!(drive.serial_speed_command().read(), Ok(Hertz(41.2)));
    // Locked again: the peer answers exception 01 to the raw device's write, the crate says
    // `Locked` (the typed API has no setter for #1 outside a guard).
    let unguarded = drive
        .device()
        .write_raw::<lenze_smd::params::Start>(lenze_smd::params::Start::TRIGGER);
    assert_eq!(
        SmdError::from(unguarded.unwrap_err()),
        SmdError::Locked { parameter: "start" }
    );
    // #48 = 0, SerialSpeedReference, #40, Start, Stop, lock.
    assert_eq!(accepted_writes(&mut drive), 6);
}

#[test]
fn pc400_places_the_moved_registers() {
    let peer = start(400);
    let (mut drive, selection) = open(&peer);
    assert_eq!(selection, VariantSelection::Known(Variant::Pc400));
    assert_eq!(
        drive.software_version().read().unwrap().as_str(),
        Some("SMD 1.51")
    );
    assert_eq!(
        drive.serial_baud_rate().read(),
        Ok(SerialBaudRate::N82_9600)
    );
    let mut session = drive.unlock_all(0).unwrap();
    session
        .acceleration_time()
        .write(drivebus::units::Seconds(10.0))
        .unwrap();
    session.lock().unwrap();
    assert_eq!(
        drive.acceleration_time().read(),
        Ok(drivebus::units::Seconds(10.0))
    );
}

#[test]
fn an_unknown_configuration_reads_but_never_writes() {
    let peer = start(600);
    let (mut drive, selection) = open(&peer);
    assert_eq!(selection, VariantSelection::Unknown(600));
    assert_eq!(drive.drive_family().read().map(|f| f.raw()), Ok(69));
    assert_eq!(
        SmdError::from(drive.unlock_controls().unwrap_err()),
        SmdError::UnknownConfiguration { value: 600 }
    );
    assert_eq!(
        SmdError::from(drive.unlock_parameter_writing(0).unwrap_err()),
        SmdError::UnknownConfiguration { value: 600 }
    );
    // The raw device's write is refused as well, before anything is sent (line 314).
    assert_eq!(
        drive
            .device()
            .write::<lenze_smd::params::SerialSpeedCommand>(Hertz(10.0)),
        Err(drivebus::Error::WritesRefused {
            parameter: "serial_speed_command",
            reason: drivebus::WriteRefusal::UnknownVariant {
                selector: "parameter_configuration",
                value: 600
            }
        })
    );
    assert_eq!(accepted_writes(&mut drive), 0, "nothing was sent");
}

/// What a drive answers a raw request: the words read, or the exception code.
type Outcome = Result<Vec<u16>, u8>;

/// The requests of the manual's rules the description states as data (FC 04 = FC 03, line 237;
/// several bits in #1, lines 569-571; FC 16 for one register only, lines 235 and 1052), sent
/// raw to `bus` at `unit`, with the outcome of each.
fn rule_requests<B: RegisterBus>(bus: &mut B, unit: UnitId) -> Vec<(&'static str, Outcome)> {
    let code = |e: drivebus::BusError| match e {
        drivebus::BusError::ModbusException { code, .. } => code.code(),
        other => panic!("no exception but {other:?}"),
    };
    let read = |bus: &mut B, table, address, count: usize| {
        let mut words = vec![0u16; count];
        bus.read_registers(unit, table, address, &mut words)
            .map(|()| words)
            .map_err(code)
    };
    let mut out = vec![
        ("FC 04 #19", read(bus, Table::Input, 19, 1)),
        (
            "FC 04 #24 x6 (length)",
            read(bus, Table::Input, 24, 6).map(|w| vec![w.len() as u16]),
        ),
        ("FC 04 #25 x2", read(bus, Table::Input, 25, 2)),
        (
            "#48 = 0",
            bus.write_register(unit, 48, 0)
                .map(|()| vec![])
                .map_err(code),
        ),
    ];
    for (what, word) in [
        ("#1 = START | UPDATE BUFFERS", 0x0009),
        ("#1 = REVERSE | FORWARD", 0x00C0),
        ("#1 = STOP | START", 0x000C),
    ] {
        out.push((
            what,
            bus.write_register(unit, 1, word)
                .map(|()| vec![])
                .map_err(code),
        ));
    }
    let fc16 = |bus: &mut B, values: &[u16]| {
        bus.write_registers(unit, 40, values)
            .map(|()| vec![])
            .map_err(code)
    };
    out.push(("FC 16 #40 x1", fc16(bus, &[100])));
    out.push(("FC 16 #40 x2", fc16(bus, &[100, 100])));
    out
}

#[test]
fn the_simulator_answers_the_manuals_rules_as_the_independent_peer_does() {
    let peer = start(507);
    let (mut drive, _) = open(&peer);
    let link = drive.device().link_mut();
    let unit = link.unit();
    let from_peer = rule_requests(link.bus_mut(), unit);

    let sim = drivesim::Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/lenze-smd"
    ))
    .unwrap();
    sim.preset("parameter_configuration", 507).unwrap();
    sim.preset("control_source", 11).unwrap();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    let mut client = drivebus::modbus::client::ModbusTcpClient::connect(
        server.local_addr(),
        &drivebus::modbus::client::TcpConfig::default(),
    )
    .unwrap();
    let from_sim = rule_requests(&mut client, UNIT);

    assert_eq!(from_sim, from_peer);
    // And they are the manual's answers, not a shared mistake.
    let expected: Vec<(&str, Outcome)> = vec![
        ("FC 04 #19", Ok(vec![69])),
        ("FC 04 #24 x6 (length)", Ok(vec![6])),
        ("FC 04 #25 x2", Err(0x03)),
        ("#48 = 0", Ok(vec![])),
        ("#1 = START | UPDATE BUFFERS", Err(0x04)),
        ("#1 = REVERSE | FORWARD", Err(0x04)),
        ("#1 = STOP | START", Ok(vec![])),
        ("FC 16 #40 x1", Ok(vec![])),
        ("FC 16 #40 x2", Err(0x03)),
    ];
    assert_eq!(from_peer, expected);
}

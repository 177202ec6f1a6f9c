//! The Kinco manual's Modbus homing and position sequences (section 10.5, lines 2489-2513) run
//! through the typed motion API against the simulated Kinco over Modbus TCP on 127.0.0.1, as
//! `motion.rs` runs them over CANopen and RS-232. The manual gives 6061h (mode display) no
//! Modbus register; the description declares 6060h's register 0x3500 read back in its place
//! (`read_back_of`, ERRATA.md #51), so `home` and `move_to` confirm the mode over Modbus too.
//! The requests are recorded and compared with the manual's frames: the same registers and
//! values, in the same order, plus the typed API's mode confirmation and polls.

use std::time::{Duration, Instant};

use drivebus::control::position::Move;
use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::{ModbusAddress, ModbusLink, UnitId};
use drivebus::testing::{LinkRequest, Recorded};
use drivebus::units::Rpm;
use drivesim::modbus::tcp::TcpServer;
use kinco_fd::types::{HomingMethod, ModesOfOperation};
use kinco_fd::KincoFd;

type Drive = KincoFd<Recorded<ModbusLink<ModbusTcpClient>, ModbusAddress>>;

fn soon(seconds: u64) -> Instant {
    Instant::now() + Duration::from_secs(seconds)
}

/// The simulated Kinco served over Modbus TCP at unit 1 while the server lives, and a recorded
/// handle to it; the manual's examples assume 10000 encoder increments (200 rpm = 0x00085555).
fn served() -> (Drive, TcpServer) {
    let description = concat!(env!("CARGO_MANIFEST_DIR"), "/../../descriptions/kinco-fd");
    let sim = drivesim::Simulator::load(description).unwrap();
    sim.preset("encoder_resolution", 10_000).unwrap();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let bus = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    let link = KincoFd::modbus(bus, UnitId(1)).into_link();
    let drive = KincoFd::new(Recorded::new(link)).give_encoder_resolution(10_000);
    (drive, server)
}

/// The writes recorded since `from`, as (register, value bytes little-endian).
fn writes(drive: &mut Drive, from: usize) -> Vec<(u16, Vec<u8>)> {
    let log = drive.device().link_mut().log();
    log[from..]
        .iter()
        .filter_map(|request| match request {
            LinkRequest::Write(address, bytes) => Some((address.address, bytes.clone())),
            LinkRequest::Read(_) => None,
        })
        .collect()
}

/// The writes of `writes` to `register`, each as its value (signed, as wide as written).
fn values_at(writes: &[(u16, Vec<u8>)], register: u16) -> Vec<i64> {
    writes
        .iter()
        .filter(|(at, _)| *at == register)
        .map(|(_, bytes)| {
            let negative = bytes.last().is_some_and(|b| b & 0x80 != 0);
            let mut le = [if negative { 0xFF } else { 0 }; 8];
            le[..bytes.len()].copy_from_slice(bytes);
            i64::from_le_bytes(le)
        })
        .collect()
}

fn log_len(drive: &mut Drive) -> usize {
    drive.device().link_mut().log().len()
}

#[test]
fn the_manuals_modbus_homing_and_position_sequences_through_the_typed_api() {
    let (mut drive, _server) = served();
    // Accelerations: the manual keeps the drive's defaults (610.352 rps/s, lines 2503-2504); the
    // simulator has none, so quick ones are set.
    drive.profile_acceleration().write_raw(1_000_000).unwrap();
    drive.profile_deceleration().write_raw(1_000_000).unwrap();
    drive.homing_acceleration().write_raw(1_000_000).unwrap();
    drive.enable_operation(soon(2)).unwrap();

    // Homing (lines 2489-2498): mode 6 at 0x3500, method 33 at 0x4D00, 200 rpm at 0x5010,
    // 150 rpm at 0x5020, controlword 0x1F; "C037 means home found".
    let from = log_len(&mut drive);
    // 200 rpm is 546133.33 DEC, no whole DEC: the typed write refuses it (scales.rs), so the
    // manual's rounded 0x00085555 goes raw; 150 rpm is exactly 0x00064000.
    drive.homing_speed_switch().write_raw(0x0008_5555).unwrap();
    drive.homing_speed_zero().write(Rpm(150.0)).unwrap();
    let home = drive.home(HomingMethod::METHOD33, soon(5)).unwrap();
    assert_eq!(home, 0);
    let sent = writes(&mut drive, from);
    assert_eq!(
        values_at(&sent, 0x5010),
        [0x0008_5555],
        "200 rpm, line 2494"
    );
    assert_eq!(
        values_at(&sent, 0x5020),
        [0x0006_4000],
        "150 rpm, line 2495"
    );
    assert_eq!(values_at(&sent, 0x3500), [6], "mode 6, line 2492");
    assert_eq!(values_at(&sent, 0x4D00), [33], "method 33, line 2493");
    assert!(
        values_at(&sent, 0x3100).contains(&0x1F),
        "controlword 0x1F, line 2496: {sent:?}"
    );
    // The mode display over Modbus is 0x3500 read back.
    assert_eq!(
        drive.modes_of_operation_display().read().unwrap(),
        ModesOfOperation::HOMING
    );

    // Position (lines 2500-2513): mode 1, 50000 inc at 0x4000, 200 rpm at 0x4A00, controlword
    // 0x2F then 0x3F (absolute); "D437 means position to". The planner raises bit 4 with the
    // move's bit 5 in one write (0x0F -> 0x3F: CiA 402 takes bit 5 at bit 4's rising edge, so
    // the manual's 0x2F first changes nothing) and drops it again at the set-point acknowledge.
    let from = log_len(&mut drive);
    drive.profile_speed().write_raw(0x0008_5555).unwrap();
    assert_eq!(drive.move_to(Move::to(50_000), soon(5)).unwrap(), 50_000);
    let sent = writes(&mut drive, from);
    assert_eq!(
        values_at(&sent, 0x4A00),
        [0x0008_5555],
        "200 rpm, line 2503"
    );
    assert_eq!(values_at(&sent, 0x3500), [1], "mode 1, line 2501");
    assert_eq!(values_at(&sent, 0x4000), [50_000], "50000 inc, line 2502");
    assert_eq!(values_at(&sent, 0x3100), [0x3F, 0x2F], "line 2507: 0x3F");
    let status = drive.statusword().read_raw().unwrap();
    assert_eq!(status & 0x0427, 0x0427, "target reached: {status:#06X}");

    // Relative (0x4F then 0x5F, lines 2508-2509): by -10000 from 50000, as a single set-point
    // (bit 5 clear, as the manual's 0x5F).
    let from = log_len(&mut drive);
    let relative = Move {
        target: -10_000,
        relative: true,
        change_immediately: false,
    };
    assert_eq!(drive.move_to(relative, soon(5)).unwrap(), 40_000);
    let sent = writes(&mut drive, from);
    assert_eq!(values_at(&sent, 0x4000), [-10_000]);
    assert_eq!(values_at(&sent, 0x3100), [0x5F, 0x4F], "line 2509: 0x5F");
}

#[test]
fn set_mode_reads_the_mode_register_back_over_modbus() {
    let (mut drive, _server) = served();
    let from = log_len(&mut drive);
    drive.set_mode(ModesOfOperation::VELOCITY, soon(2)).unwrap();
    let log = drive.device().link_mut().log()[from..].to_vec();
    let written = log
        .iter()
        .position(|r| matches!(r, LinkRequest::Write(a, _) if a.address == 0x3500))
        .expect("the mode is written to 0x3500");
    let read_back = log[written..]
        .iter()
        .any(|r| matches!(r, LinkRequest::Read(a) if a.address == 0x3500));
    assert!(read_back, "0x3500 read back after the write: {log:?}");
    assert_eq!(
        drive.modes_of_operation_display().read().unwrap(),
        ModesOfOperation::VELOCITY
    );
}

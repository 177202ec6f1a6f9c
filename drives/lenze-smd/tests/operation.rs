//! The typed crate running the simulated smd, which moves as its description says (state machine
//! `operation`, the ramp of #40 on C12 / C13): section 4.9's sequence starts the drive, the
//! output frequency #25 reaches the serial speed #40, the operational status (#26 DL, Table 11)
//! goes ACCEL → RUN, and Stop (coast, line 544) ends the output. Waits poll the drive until a
//! deadline; nothing asserts on elapsed time.

#[path = "support/simulated_smd.rs"]
mod simulated_smd;

use std::time::{Duration, Instant};

use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::{ModbusLink, UnitId};
use drivebus::units::Hertz;
use drivesim::modbus::tcp::TcpServer;
use drivesim::Simulator;
use lenze_smd::operation::State;
use lenze_smd::types::{HardwareConfiguration, OperationalStatus};
use lenze_smd::{Command, LenzeSmd, SmdError};

const UNIT: UnitId = UnitId(10);

type Drive = LenzeSmd<ModbusLink<ModbusTcpClient>>;

/// A simulated PC507 smd under Modbus control (C01 = 11) with these further presets.
fn simulated(presets: &[(&str, i128)]) -> (Simulator, TcpServer) {
    let sim = simulated_smd::pc507_under_modbus(presets);
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    (sim, server)
}

fn connect(server: &TcpServer) -> Drive {
    let client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    LenzeSmd::open(client, UNIT).unwrap().0
}

/// Polls the status block until `done` holds for it, or fails after 10 s with the last block.
fn wait_for(
    drive: &mut Drive,
    what: &str,
    done: impl Fn(&lenze_smd::StatusBlock) -> bool,
) -> lenze_smd::StatusBlock {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let status = drive.status().unwrap();
        if done(&status) {
            return status;
        }
        assert!(Instant::now() < deadline, "{what}: last status {status:?}");
        std::thread::sleep(Duration::from_millis(10));
    }
}

#[test]
fn start_accelerates_to_the_serial_speed_and_stop_coasts() {
    // C12 = 0.5 s from 0 to C11 = 50 Hz (ERRATA.md E21): 41.2 Hz in about 0.4 s.
    let (_sim, server) = simulated(&[("acceleration_time", 5)]);
    let mut drive = connect(&server);
    assert_eq!(
        drive.drive_family().read().unwrap(),
        lenze_smd::types::DriveFamily::SMD
    );
    assert_eq!(drive.operation_state().unwrap(), Some(State::Stopped));
    let mut unlocked = drive.unlock_controls().unwrap();
    unlocked.command(Command::SerialSpeedReference).unwrap();
    unlocked
        .serial_speed_command()
        .write(Hertz(41.2))
        .map_err(SmdError::from)
        .unwrap();
    unlocked.command(Command::Start).unwrap();
    let first = unlocked.drive().status().unwrap();
    assert_eq!(first.command_speed, Hertz(41.2));
    assert_eq!(
        first.load_and_status.operational_status(),
        OperationalStatus::ACCEL,
        "{first:?}"
    );
    let running = wait_for(unlocked.drive(), "at speed", |s| {
        s.actual_speed == Hertz(41.2)
    });
    assert_eq!(
        running.load_and_status.operational_status(),
        OperationalStatus::RUN
    );
    assert_eq!(
        unlocked.drive().operation_state().unwrap(),
        Some(State::Running)
    );
    unlocked.command(Command::Stop).unwrap();
    let stopped = unlocked.drive().status().unwrap();
    assert_eq!(
        stopped.load_and_status.operational_status(),
        OperationalStatus::STOP
    );
    assert_eq!(stopped.actual_speed, Hertz(0.0));
    unlocked.lock().unwrap();
}

#[test]
fn the_generated_machine_walks_to_running_and_back() {
    let (_sim, server) = simulated(&[("acceleration_time", 0), ("serial_speed_command", 300)]);
    let mut drive = connect(&server);
    let mut unlocked = drive.unlock_controls().unwrap();
    let deadline = Instant::now() + Duration::from_secs(5);
    unlocked
        .drive()
        .goto_operation(State::Running, deadline)
        .unwrap();
    let status = wait_for(unlocked.drive(), "at 30 Hz", |s| {
        s.actual_speed == Hertz(30.0)
    });
    assert_eq!(
        status.load_and_status.operational_status(),
        OperationalStatus::RUN
    );
    unlocked
        .drive()
        .goto_operation(State::Stopped, deadline)
        .unwrap();
    assert_eq!(unlocked.drive().actual_speed().read().unwrap(), Hertz(0.0));
}

#[test]
fn table_9_bit_3_reads_as_epm_user_data_compatible_only() {
    // Table 9 (lines 604-607): bit 2 OEM defaults present, bit 3 EPM user data compatible only.
    let (_sim, server) = simulated(&[("hardware_configuration", 0x0008)]);
    let mut drive = connect(&server);
    let flags = drive.hardware_configuration().read().unwrap();
    assert!(flags.contains(HardwareConfiguration::EPM_USER_DATA_COMPATIBLE_ONLY));
    assert!(!flags.contains(HardwareConfiguration::OEM_DEFAULTS_PRESENT));
}

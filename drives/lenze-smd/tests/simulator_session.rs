//! The generated unlock guard against the simulator serving the same description: the drive's
//! own lock rules (exception 01 while locked), the end of an unlock by a C01 change and by the
//! watchdog (n22 = 3 trips FC3 after n23 ms of silence), and the keep-alive that prevents it,
//! polling over a second connection while the guard is held.

use std::sync::{Arc, Mutex};
use std::thread::sleep;
use std::time::Duration;

use drivebus::modbus::transport::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::{ModbusLink, UnitId};
use drivebus::units::Seconds;
use drivesim::modbus::tcp::TcpServer;
use drivesim::Simulator;
use lenze_smd::types::ControlSource;
use lenze_smd::{Command, KeepAlive, LenzeSmd, UnlockError};

const UNIT: UnitId = UnitId(10);

type Drive = LenzeSmd<ModbusLink<ModbusTcpClient>>;

/// A simulated PC507 smd under Modbus control with these further presets.
fn simulated(presets: &[(&str, i128)]) -> (Simulator, TcpServer) {
    let sim = Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/lenze-smd"
    ))
    .unwrap();
    sim.preset("parameter_configuration", 507).unwrap();
    sim.preset("control_source", 11).unwrap();
    for (name, value) in presets {
        sim.preset(name, *value).unwrap();
    }
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UNIT).unwrap();
    (sim, server)
}

fn connect(server: &TcpServer) -> Drive {
    let client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    LenzeSmd::open(client, UNIT).unwrap().0
}

#[test]
fn the_guard_writes_what_its_unlock_opens_and_locks_on_drop() {
    let (_sim, server) = simulated(&[]);
    let mut drive = connect(&server);
    {
        let mut unlocked = drive.unlock_controls().unwrap();
        unlocked.command(Command::Start).unwrap();
    } // dropped: #1 = 0x0002
    let mut unlocked = drive.unlock_parameter_writing(0).unwrap();
    unlocked.acceleration_time().write(Seconds(2.5)).unwrap();
    // The parameter guard has no `command`; the drive refuses #1 as well (line 421).
    let refused = unlocked
        .drive()
        .device()
        .write_raw::<lenze_smd::params::Start>(lenze_smd::params::Start::TRIGGER)
        .unwrap_err();
    assert_eq!(
        UnlockError::from(refused),
        UnlockError::Locked { parameter: "start" }
    );
    unlocked.lock().unwrap();
    assert_eq!(drive.acceleration_time().read().unwrap(), Seconds(2.5));
}

#[test]
fn monitoring_only_c01_refuses_the_unlock_before_sending() {
    let (_sim, server) = simulated(&[("control_source", 8)]);
    let mut drive = connect(&server);
    assert_eq!(
        drive.unlock_controls().unwrap_err(),
        UnlockError::Requirement {
            parameter: "control_source",
            found: 8,
            allowed: &[10, 11]
        }
    );
}

#[test]
fn changing_c01_ends_the_unlock() {
    let (_sim, server) = simulated(&[]);
    let mut drive = connect(&server);
    let mut unlocked = drive.unlock_all(0).unwrap();
    unlocked
        .control_source()
        .write(ControlSource::ANALOG_TERMINAL_MODBUS)
        .unwrap();
    assert_eq!(
        unlocked.command(Command::Start),
        Err(UnlockError::Locked { parameter: "start" })
    );
}

#[test]
fn a_serial_timeout_ends_the_unlock_unless_kept_alive() {
    // n22 = 3 (trip FC3), n23 = 300 ms (lines 385-387).
    let presets = [("serial_timeout_action", 3), ("serial_fault_time", 300)];
    let (sim, server) = simulated(&presets);
    let mut drive = connect(&server);
    let mut unlocked = drive.unlock_controls().unwrap();
    sleep(Duration::from_millis(600));
    assert_eq!(
        unlocked.command(Command::Start),
        Err(UnlockError::Locked { parameter: "start" })
    );
    assert_eq!(sim.with(|d| d.fault()), Some(24), "FC3 (line 1007)");
    drop(unlocked);

    // The same with a keep-alive polling the status block over a second connection.
    let (sim, server) = simulated(&presets);
    let mut drive = connect(&server);
    let watcher = Arc::new(Mutex::new(connect(&server)));
    let keep_alive = KeepAlive::for_drive(watcher).unwrap().expect("n22 is 3");
    let mut unlocked = drive.unlock_controls().unwrap();
    sleep(Duration::from_millis(600));
    assert_eq!(unlocked.command(Command::Start), Ok(()));
    assert_eq!(sim.with(|d| d.fault()), None);
    unlocked.lock().unwrap();
    assert!(keep_alive.report().polls > 0);
}

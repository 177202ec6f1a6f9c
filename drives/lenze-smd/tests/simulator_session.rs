//! The generated unlock guard against the simulator serving the same description: the drive's
//! own lock rules (exception 01 while locked), the end of an unlock by a C01 change and by the
//! watchdog (n22 = 3 trips FC3 after n23 ms of silence), and the keep-alive that prevents it,
//! polling over a second connection while the guard is held. And the untyped path
//! (`drive.device().write_raw(..)`): a write to a locked parameter is refused before it is sent.

#[path = "support/simulated_smd.rs"]
mod simulated_smd;

use std::sync::{Arc, Mutex};
use std::thread::sleep;
use std::time::Duration;

use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::{ModbusLink, RegisterBus, Table, UnitId};
use drivebus::units::Seconds;
use drivebus::{BusError, Error, WriteRefusal};
use drivesim::modbus::tcp::TcpServer;
use drivesim::Simulator;
use lenze_smd::types::ControlSource;
use lenze_smd::{params, Command, KeepAlive, LenzeSmd, UnlockError};

const UNIT: UnitId = UnitId(10);

type Drive = LenzeSmd<ModbusLink<ModbusTcpClient>>;

/// A simulated PC507 smd under Modbus control with these further presets.
fn simulated(presets: &[(&str, i128)]) -> (Simulator, TcpServer) {
    let sim = simulated_smd::pc507_under_modbus(presets);
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

/// A Modbus TCP client that counts the writes it sends.
struct CountingWrites {
    client: ModbusTcpClient,
    writes: usize,
}

impl RegisterBus for CountingWrites {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        self.client.read_registers(unit, table, start, out)
    }

    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        self.writes += 1;
        self.client.write_register(unit, address, value)
    }

    fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        self.writes += 1;
        self.client.write_registers(unit, start, values)
    }
}

type CountedDrive = LenzeSmd<ModbusLink<CountingWrites>>;

fn connect_counting(server: &TcpServer) -> CountedDrive {
    let client = ModbusTcpClient::connect(server.local_addr(), &TcpConfig::default()).unwrap();
    let writes = CountingWrites { client, writes: 0 };
    LenzeSmd::open(writes, UNIT).unwrap().0
}

fn writes_sent(drive: &mut CountedDrive) -> usize {
    drive.device().link_mut().bus_mut().writes
}

/// What the handle answers a write to a locked parameter of the `parameters` scope.
fn locked_parameter(parameter: &'static str) -> Error {
    Error::WritesRefused {
        parameter,
        reason: WriteRefusal::Locked {
            scope: "parameters",
            opened_by: &["all", "parameter_writing"],
        },
    }
}

#[test]
fn the_untyped_path_refuses_a_locked_write_before_sending_and_writes_once_unlocked() {
    let (sim, server) = simulated(&[]);
    let mut drive = connect_counting(&server);
    let c12 = || sim.with(|d| d.store().int(d.store().id("acceleration_time").unwrap()));
    let before = c12();

    let refused = drive
        .device()
        .write::<params::AccelerationTime>(Seconds(2.5))
        .unwrap_err();
    assert_eq!(refused, locked_parameter("acceleration_time"));
    assert!(refused.to_string().contains("`all` or `parameter_writing`"));
    assert_eq!(writes_sent(&mut drive), 0, "nothing was sent");
    assert_eq!(c12(), before);

    // #49 = C94 (0 here) through the same untyped path (line 423): the parameters open.
    drive
        .device()
        .write_raw::<params::UnlockParameters>(0)
        .unwrap();
    drive
        .device()
        .write::<params::AccelerationTime>(Seconds(2.5))
        .unwrap();
    assert_eq!(c12(), Some(25));
    // #49 opens no control (line 423): #1 stays refused before sending.
    let start = drive
        .device()
        .write_raw::<params::Start>(params::Start::TRIGGER)
        .unwrap_err();
    assert_eq!(
        UnlockError::from(start),
        UnlockError::Locked { parameter: "start" }
    );
    assert_eq!(writes_sent(&mut drive), 2);

    // #1 bit 1 locks everything again (line 415).
    drive
        .device()
        .write_raw::<params::LockSecurity>(params::LockSecurity::TRIGGER)
        .unwrap();
    assert_eq!(
        drive
            .device()
            .write::<params::AccelerationTime>(Seconds(3.0))
            .unwrap_err(),
        locked_parameter("acceleration_time")
    );
    assert_eq!(writes_sent(&mut drive), 3);
    assert_eq!(c12(), Some(25));
}

#[test]
fn a_locked_answer_teaches_the_handle_to_refuse_before_sending() {
    // C94 = 5: #49 = 7 is the wrong password, which only the drive can tell (line 423).
    let (_sim, server) = simulated(&[("user_password", 5)]);
    let mut drive = connect_counting(&server);
    drive
        .device()
        .write_raw::<params::UnlockParameters>(7)
        .unwrap();
    let answered = drive
        .device()
        .write::<params::AccelerationTime>(Seconds(2.5))
        .unwrap_err();
    assert_eq!(
        UnlockError::from(answered),
        UnlockError::Locked {
            parameter: "acceleration_time"
        },
        "the drive answered exception 01"
    );
    assert_eq!(writes_sent(&mut drive), 2);
    assert_eq!(
        drive
            .device()
            .write::<params::DecelerationTime>(Seconds(2.5))
            .unwrap_err(),
        locked_parameter("deceleration_time")
    );
    assert_eq!(writes_sent(&mut drive), 2, "the second write was not sent");
    drive
        .device()
        .write_raw::<params::UnlockParameters>(5)
        .unwrap();
    drive
        .device()
        .write::<params::DecelerationTime>(Seconds(2.5))
        .unwrap();
    assert_eq!(writes_sent(&mut drive), 4);
}

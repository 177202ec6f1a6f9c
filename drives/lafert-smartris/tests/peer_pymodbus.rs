//! The generated Lafert API against an independent Modbus implementation: pymodbus 3.16.1 serving
//! a Lafert-like register map over Modbus TCP on 127.0.0.1 (tests/peers/modbus_server.py), reached
//! with drivebus' TCP client. The test starts the server and stops it by PID.
//!
//! Python comes from `DRIVEGEN_PYTHON`, else `.venv/bin/python` at the workspace root, else
//! `python3`. A missing peer fails the test with instructions; `tests/peers/setup.sh` installs it.

use std::time::Duration;

use drivebus::modbus::client::{ModbusTcpClient, TcpConfig};
use drivebus::modbus::{ExceptionCode, ModbusLink, UnitId};
use drivebus::units::{Rpm, Volts};
use drivebus::BusError;
use lafert_smartris::types::{ControlWord, DriveStatus, WarningCode};
use lafert_smartris::{params, RebootWait, Smartris, StdClock, StoreResetError};

#[path = "support/pymodbus_server.rs"]
mod pymodbus_server;
use pymodbus_server::{start_server, start_server_with, Server};

fn connect(server: &Server) -> Smartris<ModbusLink<ModbusTcpClient>> {
    let config = TcpConfig {
        timeout: Duration::from_secs(2),
        ..TcpConfig::default()
    };
    let client = ModbusTcpClient::connect(&server.address, &config).expect("connect to pymodbus");
    Smartris::modbus(client, UnitId(1))
}

fn exception(function: u8, code: ExceptionCode) -> Option<BusError> {
    Some(BusError::ModbusException { function, code })
}

#[test]
fn typed_reads_of_input_registers() {
    let server = start_server();
    let mut drive = connect(&server);
    // The server's input registers hold 0x1000 + address.
    let status = drive.drive_status().read().unwrap();
    assert!(status.contains(DriveStatus::RUN_TORQUE | DriveStatus::INIT));
    assert_eq!(status.bits(), 0x1060, "undocumented bits survive");
    assert_eq!(drive.bus_dc_link().read(), Ok(Volts(41.96)));
    // 32-bit LOW/HIGH pairs: AXIS POSITION 0x006B = 0x5678, 0x006C = 0x1234.
    assert_eq!(drive.axis_position().read_raw(), Ok(0x1234_5678));
    assert_eq!(
        drive.warning_code().read().map(|w| w.bits()),
        Ok(0x1062_1061)
    );
    let (status, warnings, error, volts) = drive
        .read_many((
            params::DriveStatus,
            params::WarningCode,
            params::ErrorCode,
            params::BusDcLink,
        ))
        .unwrap();
    assert_eq!(status.bits(), 0x1060);
    // 0x1061 has bits 0, 5, 6 and 12 set: no temperature warning (bits 8-10).
    assert_eq!(warnings.bits(), 0x1062_1061);
    assert!(!warnings.intersects(
        WarningCode::HEAT_SINK_TEMPERATURE
            | WarningCode::LOGIC_BOARD_TEMPERATURE
            | WarningCode::MOTOR_TEMPERATURE
    ));
    assert_eq!((error.raw(), error.is_known()), (0x1063, false));
    assert_eq!(volts, Volts(41.96));
}

#[test]
fn writes_and_reads_back_holding_registers() {
    let server = start_server();
    let mut drive = connect(&server);
    assert_eq!(drive.modbus_address().read(), Ok(1));
    drive.modbus_address().write(2).unwrap();
    assert_eq!(drive.modbus_address().read(), Ok(2));
    let run = ControlWord::RUN | ControlWord::STOP_DISABLED;
    drive.control_word().write(run).unwrap();
    assert_eq!(drive.control_word().read(), Ok(run));
    drive.speed_setpoint().write(Rpm(3000.0)).unwrap();
}

#[test]
fn an_unknown_register_is_exception_0x02() {
    let server = start_server();
    let mut drive = connect(&server);
    // FEEDBACK TYPE, input 0x0100: the server has no input registers there.
    let error = drive.feedback_type_actual().read().unwrap_err();
    assert_eq!(
        error.bus().cloned(),
        exception(0x04, ExceptionCode::IllegalDataAddress)
    );
}

#[test]
fn a_write_the_drive_refuses_is_exception_0x03() {
    let server = start_server();
    let mut drive = connect(&server);
    // 3500 rpm fits the register, but not the full-scale velocity (3000 rpm) the server enforces.
    // The typed write reads that bound (holding 0x0003) first and sends nothing.
    let before = setpoint_register(&mut drive);
    assert_eq!(
        drive.speed_setpoint().write(Rpm(3500.0)),
        Err(drivebus::Error::OutsideBound(drivebus::OutsideBound {
            parameter: "speed_setpoint",
            bound: "full_scale_velocity",
            raw: 3500,
            limit: 3000,
        }))
    );
    assert_eq!(
        setpoint_register(&mut drive),
        before,
        "the server saw no write"
    );
    // Past the typed API, the drive itself answers the same value with exception 0x03.
    use drivebus::modbus::RegisterBus;
    let refused = drive
        .device()
        .link_mut()
        .bus_mut()
        .write_register(UnitId(1), 0x0042, 3500);
    assert_eq!(
        refused.err(),
        exception(0x06, ExceptionCode::IllegalDataValue)
    );
}

#[test]
fn store_and_reset_reports_the_refused_reset() {
    let server = start_server();
    let mut drive = connect(&server);
    // The server stores (holding 0x0000 exists) but has no 0xA5A5: the reset step fails typed.
    let error = drive
        .store_and_reset(RebootWait::default(), &mut StdClock::new())
        .unwrap_err();
    let StoreResetError::Reset(cause) = &error else {
        panic!("expected the reset step to fail, got {error:?}");
    };
    assert_eq!(
        cause.bus().cloned(),
        exception(0x06, ExceptionCode::IllegalDataAddress)
    );
}

/// The speed setpoint register (holding 0x0042) as the server holds it, read around the API.
fn setpoint_register(drive: &mut Smartris<ModbusLink<ModbusTcpClient>>) -> u16 {
    use drivebus::modbus::{RegisterBus, Table};
    let mut word = [0u16; 1];
    let bus = drive.device().link_mut().bus_mut();
    bus.read_registers(UnitId(1), Table::Holding, 0x0042, &mut word)
        .unwrap();
    word[0]
}

#[test]
fn a_drive_reporting_a_foreign_firmware_gets_no_write() {
    // pymodbus holds FW RELEASE CUSTOMER (0x01FF) = 226, firmware 2.2.6 (manual line 1022's
    // example); the description covers 242 only (guide line 180).
    let server = start_server_with(&["--firmware", "226"]);
    let mut drive = connect(&server);
    let mismatch = drivebus::WriteRefusal::IdentityMismatch {
        parameter: "fw_release",
        expected: &[242],
        found: 226,
    };
    assert_eq!(
        drive.verify_identity(),
        Err(drivebus::Error::WritesRefused {
            parameter: "fw_release",
            reason: mismatch
        })
    );
    let before = setpoint_register(&mut drive);
    assert_eq!(
        drive.speed_setpoint().write(Rpm(1500.0)),
        Err(drivebus::Error::WritesRefused {
            parameter: "speed_setpoint",
            reason: mismatch
        })
    );
    assert_eq!(
        setpoint_register(&mut drive),
        before,
        "the server saw no write"
    );
}

#[test]
fn the_covered_firmware_verifies_and_is_written() {
    let server = start_server_with(&["--firmware", "242"]);
    let mut drive = connect(&server);
    assert_eq!(drive.verify_identity(), Ok(()));
    assert_eq!(drive.speed_setpoint().write(Rpm(1500.0)), Ok(()));
    assert_eq!(setpoint_register(&mut drive), 1500);
}

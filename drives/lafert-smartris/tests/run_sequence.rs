//! The Modbus run sequence (manual §4.2.1, guide §7.6) against a scripted drive.

#[path = "support/simulated_drive.rs"]
mod simulated_drive;

use drivebus::modbus::{ModbusLink, UnitId};
use drivebus::units::{AmperesRms, Rpm};
use drivebus::ErrorClass;
use lafert_smartris::types::{DriveStatus, ErrorCode, OperationMode};
use lafert_smartris::{ControlMode, RunError, Smartris};
use simulated_drive::{SimulatedDrive, CONTROL_WORD, SAFE, STOP};

const SPEED_SETPOINT: u16 = 0x0042;
const TORQUE_SETPOINT: u16 = 0x0047;

fn drive(sim: SimulatedDrive) -> Smartris<ModbusLink<SimulatedDrive>> {
    Smartris::modbus(sim, UnitId(1))
}

fn writes(drive: Smartris<ModbusLink<SimulatedDrive>>) -> Vec<(u16, u16)> {
    drive.into_link().into_bus().writes()
}

#[test]
fn velocity_mode_enable_speed_ramp_stop_and_standby() {
    let mut drive = drive(SimulatedDrive::in_standby(2));
    let status = drive.enable(ControlMode::Velocity).unwrap();
    assert!(status.contains(DriveStatus::RUN_VELOCITY));
    // Step 7 example: 0x03E8 → 1000 rpm (manual line 1208, guide line 6593).
    drive.set_speed(Rpm(1000.0)).unwrap();
    drive.stop_with_ramp().unwrap();
    assert!(drive.stop().unwrap().contains(DriveStatus::STOP));
    assert!(drive.standby().unwrap().contains(DriveStatus::STANDBY));
    assert_eq!(
        writes(drive),
        [
            (CONTROL_WORD, 0x0003),
            (SPEED_SETPOINT, 1000),
            (SPEED_SETPOINT, 0),
            (CONTROL_WORD, 0x0001),
            (CONTROL_WORD, 0x0002),
        ]
    );
}

#[test]
fn torque_mode_setpoint_of_10_arms_is_1000() {
    // Step 7 example: 0x03E8 (1000 → 10 Arms), manual line 1210, guide line 6597.
    let mut drive = drive(SimulatedDrive::in_standby(1));
    drive.enable(ControlMode::Torque).unwrap();
    drive.set_torque(AmperesRms(10.0)).unwrap();
    assert_eq!(
        writes(drive),
        [(CONTROL_WORD, 0x0003), (TORQUE_SETPOINT, 1000)]
    );
}

#[test]
fn enable_in_alarm_reports_the_decoded_error_code_and_sends_nothing() {
    let mut drive = drive(SimulatedDrive::in_standby(2).with_alarm(0x2340));
    let error = drive.enable(ControlMode::Velocity).unwrap_err();
    let RunError::InAlarm { code } = error.clone() else {
        panic!("expected InAlarm, got {error:?}");
    };
    assert_eq!(code, ErrorCode::SHORT_CIRCUIT_MOTOR);
    assert_eq!(code.class(), Some(ErrorClass::Fault));
    assert_eq!(code.led_code(), Some((3, 1)));
    assert!(error.to_string().contains("0x2340"), "{error}");
    assert!(writes(drive).is_empty());
}

#[test]
fn enable_in_the_wrong_mode_says_which_mode_the_drive_is_in() {
    let mut drive = drive(SimulatedDrive::in_standby(1));
    assert_eq!(
        drive.enable(ControlMode::Velocity),
        Err(RunError::WrongMode {
            expected: OperationMode::VELOCITY,
            actual: OperationMode::TORQUE
        })
    );
    assert!(writes(drive).is_empty());
}

#[test]
fn enable_with_sto_active_is_refused() {
    let mut drive = drive(SimulatedDrive::in_standby(2).with_status(SAFE));
    assert_eq!(
        drive.enable(ControlMode::Velocity),
        Err(RunError::SafeTorqueOff)
    );
}

#[test]
fn a_drive_that_does_not_start_is_reported_with_its_status() {
    let mut sim = SimulatedDrive::in_standby(2);
    sim.obeys_run = false;
    let mut drive = drive(sim);
    assert_eq!(
        drive.enable(ControlMode::Velocity),
        Err(RunError::WrongState {
            expected: DriveStatus::RUN_VELOCITY,
            status: DriveStatus::STANDBY
        })
    );
}

#[test]
fn enable_from_stop_is_transition_t5() {
    let mut drive = drive(SimulatedDrive::in_standby(2).with_status(STOP));
    assert!(drive.enable(ControlMode::Velocity).is_ok());
}

#[test]
fn a_torque_setpoint_in_velocity_mode_is_not_sent() {
    let mut drive = drive(SimulatedDrive::in_standby(2));
    drive.enable(ControlMode::Velocity).unwrap();
    assert!(matches!(
        drive.set_torque(AmperesRms(1.0)),
        Err(RunError::WrongState { .. })
    ));
    assert_eq!(writes(drive), [(CONTROL_WORD, 0x0003)]);
}

#[test]
fn an_out_of_range_speed_is_a_typed_value_error() {
    let mut drive = drive(SimulatedDrive::in_standby(2));
    drive.enable(ControlMode::Velocity).unwrap();
    assert!(matches!(
        drive.set_speed(Rpm(40_000.0)),
        Err(RunError::Bus(drivebus::Error::Value(_)))
    ));
}

#[test]
fn the_async_steps_send_what_the_blocking_steps_send() {
    use drivebus::asynch::Async;
    use drivebus::testing::{now, Immediate};
    let link = drive(SimulatedDrive::in_standby(2)).into_link();
    let mut awaited = Smartris::new(Async(Immediate(link)));
    let status = now(awaited.enable_async(ControlMode::Velocity)).unwrap();
    assert!(status.unwrap().contains(DriveStatus::RUN_VELOCITY));
    now(awaited.set_speed_async(Rpm(1000.0))).unwrap().unwrap();
    now(awaited.stop_with_ramp_async()).unwrap().unwrap();
    let stopped = now(awaited.stop_async()).unwrap().unwrap();
    assert!(stopped.contains(DriveStatus::STOP));
    let standby = now(awaited.standby_async()).unwrap().unwrap();
    assert!(standby.contains(DriveStatus::STANDBY));
    // Torque needs the torque mode: refused before anything is written, as by `enable`.
    assert_eq!(
        now(awaited.enable_async(ControlMode::Torque)).unwrap(),
        Err(RunError::WrongMode {
            expected: OperationMode::TORQUE,
            actual: OperationMode::VELOCITY,
        })
    );
    let sent = awaited.into_link().0 .0.into_bus().writes();

    let mut blocking = drive(SimulatedDrive::in_standby(2));
    blocking.enable(ControlMode::Velocity).unwrap();
    blocking.set_speed(Rpm(1000.0)).unwrap();
    blocking.stop_with_ramp().unwrap();
    blocking.stop().unwrap();
    blocking.standby().unwrap();
    assert!(blocking.enable(ControlMode::Torque).is_err());
    assert_eq!(sent, writes(blocking));
}

#[test]
fn an_async_step_in_alarm_reports_the_decoded_error_code() {
    use drivebus::asynch::Async;
    use drivebus::testing::{now, Immediate};
    let link = drive(SimulatedDrive::in_standby(2).with_alarm(0x2340)).into_link();
    let mut awaited = Smartris::new(Async(Immediate(link)));
    let refused = now(awaited.enable_async(ControlMode::Velocity)).unwrap();
    let mut blocking = drive(SimulatedDrive::in_standby(2).with_alarm(0x2340));
    assert_eq!(refused, blocking.enable(ControlMode::Velocity));
    assert!(
        matches!(refused, Err(RunError::InAlarm { .. })),
        "{refused:?}"
    );
    assert!(awaited.into_link().0 .0.into_bus().writes().is_empty());
}

//! The generated unlock sessions (`[lock]` / `[[unlock]]` in the description) against a drive
//! double that enforces the manual's lock rules (sections 4.5, 4.6): the C01 requirement checked
//! before anything is written, one command bit per write, the C10...C11 bound of #40, lock on
//! `lock()` and on drop, and exception 01 as `Locked`.

#[path = "support/smd_double.rs"]
mod smd_double;

use drivebus::modbus::{ModbusLink, UnitId};
use drivebus::units::{Hertz, Seconds};
use lenze_smd::{Command, LenzeSmd, SmdError, UnlockError};
use smd_double::*;

type Drive = LenzeSmd<ModbusLink<SmdDouble>>;

fn drive(double: SmdDouble) -> Drive {
    LenzeSmd::modbus(double, UnitId(10))
}

fn accepted(drive: Drive) -> Vec<(u16, u16)> {
    drive.into_link().into_bus().accepted
}

#[test]
fn control_session_commands_and_locks() {
    let mut d = drive(SmdDouble::pc507(11, 0));
    let mut session = d.unlock_controls().unwrap();
    session.command(Command::SerialSpeedReference).unwrap();
    session.serial_speed_command().write(Hertz(41.2)).unwrap();
    session.command(Command::Start).unwrap();
    session.command(Command::Stop).unwrap();
    session.lock().unwrap();
    // Past the guard, only the raw device can still write #1: the drive refuses it.
    let error = d.device().write_raw::<lenze_smd::params::Start>(0x0008);
    assert_eq!(
        SmdError::from(error.unwrap_err()),
        SmdError::Locked { parameter: "start" }
    );
    assert_eq!(
        accepted(d),
        [
            (UNLOCK_CONTROLS, 0),
            (DRIVE_CONTROL, 0x0100),
            (SERIAL_SPEED, 412),
            (DRIVE_CONTROL, 0x0008),
            (DRIVE_CONTROL, 0x0004),
            (DRIVE_CONTROL, 0x0002),
        ]
    );
}

#[test]
fn dropping_a_session_locks_the_drive() {
    let mut d = drive(SmdDouble::pc507(10, 0));
    {
        let mut session = d.unlock_controls().unwrap();
        session.command(Command::Forward).unwrap();
    }
    let double = d.into_link().into_bus();
    assert!(!double.controls_unlocked);
    assert_eq!(double.accepted.last(), Some(&(DRIVE_CONTROL, 0x0002)));
}

#[test]
fn serial_control_needs_c01_10_or_11_and_nothing_is_written_otherwise() {
    let mut d = drive(SmdDouble::pc507(8, 0));
    let refused = d.unlock_controls().unwrap_err();
    assert_eq!(
        refused,
        UnlockError::Requirement {
            parameter: "control_source",
            found: 8,
            allowed: &[10, 11]
        }
    );
    assert!(refused.to_string().contains("control_source is 8"));
    assert_eq!(
        d.unlock_all(0).unwrap_err(),
        refused,
        "#48 = C94 unlocks the controls too"
    );
    assert!(accepted(d).is_empty());
}

#[test]
fn an_unknown_configuration_refuses_writes_but_reads_work() {
    let mut double = SmdDouble::pc507(11, 0);
    double
        .memory
        .set_register(drivebus::modbus::Table::Holding, CONFIGURATION, 600);
    let (mut d, _) = LenzeSmd::open(double, UnitId(10)).unwrap();
    let refused = SmdError::UnknownConfiguration { value: 600 };
    assert_eq!(SmdError::from(d.unlock_controls().unwrap_err()), refused);
    assert_eq!(SmdError::from(d.unlock_all(0).unwrap_err()), refused);
    assert_eq!(
        SmdError::from(d.unlock_parameter_writing(0).unwrap_err()),
        refused
    );
    assert!(refused.to_string().contains("600"));
    assert_eq!(d.control_source().read().unwrap().raw(), 11);
    assert!(accepted(d).is_empty());
}

#[test]
fn the_serial_speed_stays_within_c10_and_c11() {
    let mut double = SmdDouble::pc507(11, 0);
    double
        .memory
        .set_register(drivebus::modbus::Table::Holding, C10, 100);
    let mut d = drive(double);
    let mut session = d.unlock_controls().unwrap();
    assert_eq!(
        SmdError::from(
            session
                .serial_speed_command()
                .write(Hertz(9.9))
                .unwrap_err()
        ),
        SmdError::OutsideBound(drivebus::OutsideBound {
            parameter: "serial_speed_command",
            bound: "minimum_output_frequency",
            raw: 99,
            limit: 100,
        })
    );
    let above = SmdError::from(
        session
            .serial_speed_command()
            .write(Hertz(50.1))
            .unwrap_err(),
    );
    assert!(matches!(
        above,
        SmdError::OutsideBound(drivebus::OutsideBound {
            bound: "maximum_output_frequency",
            ..
        })
    ));
    session.serial_speed_command().write(Hertz(50.0)).unwrap();
    drop(session);
    let writes = accepted(d);
    let speeds: Vec<_> = writes.iter().filter(|(r, _)| *r == SERIAL_SPEED).collect();
    assert_eq!(speeds, [&(SERIAL_SPEED, 500)]);
}

#[test]
fn parameter_session_writes_with_the_right_password_only() {
    let mut d = drive(SmdDouble::pc507(9, 123));
    let mut wrong = d.unlock_parameter_writing(7).unwrap();
    assert_eq!(
        UnlockError::from(wrong.acceleration_time().write(Seconds(10.0)).unwrap_err()),
        UnlockError::Locked {
            parameter: "acceleration_time"
        }
    );
    drop(wrong);
    let mut right = d.unlock_parameter_writing(123).unwrap();
    right.acceleration_time().write(Seconds(10.0)).unwrap();
    right.lock().unwrap();
    let writes = accepted(d);
    assert!(writes.contains(&(C12, 100)));
}

#[test]
fn unlock_all_allows_commands_and_parameters() {
    let mut d = drive(SmdDouble::pc507(11, 5));
    let mut session = d.unlock_all(5).unwrap();
    session.command(Command::Reverse).unwrap();
    session.acceleration_time().write(Seconds(2.5)).unwrap();
    session.lock().unwrap();
    let writes = accepted(d);
    assert_eq!(
        writes,
        [
            (UNLOCK_CONTROLS, 5),
            (DRIVE_CONTROL, 0x0040),
            (C12, 25),
            (DRIVE_CONTROL, 0x0002)
        ]
    );
}

#[test]
fn an_unlock_the_drive_ended_surfaces_as_locked() {
    // A serial timeout or a C01 change ends the unlock (line 414): the next write gets 01.
    let mut d = drive(SmdDouble::pc507(11, 0));
    let mut session = d.unlock_controls().unwrap();
    session.command(Command::Start).unwrap();
    session
        .drive()
        .device()
        .link_mut()
        .bus_mut()
        .controls_unlocked = false;
    assert_eq!(
        session.command(Command::Stop).unwrap_err(),
        UnlockError::Locked { parameter: "stop" }
    );
}

#[test]
fn every_command_is_one_bit() {
    for command in Command::ALL {
        assert_eq!(command.word().count_ones(), 1, "{command:?}");
    }
}

#[test]
fn locking_a_drive_that_locked_itself_succeeds() {
    let mut d = drive(SmdDouble::pc507(11, 0));
    let mut session = d.unlock_controls().unwrap();
    session
        .drive()
        .device()
        .link_mut()
        .bus_mut()
        .controls_unlocked = false;
    assert_eq!(session.lock(), Ok(()));
}

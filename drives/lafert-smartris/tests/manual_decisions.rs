//! The values the fidelity review of #27 found wrong or undecided, as the manuals give them
//! (user guide `000_ac225e0ba9cf582c.txt`, Modbus manual `001_ad8624675505a5b5.txt`; ERRATA.md
//! has the decisions): typed through the generated API over an in-memory bus, and the factory
//! defaults on the simulated drive.

use std::time::{Duration, Instant};

use drivebus::canopen::NodeId;
use drivebus::control::driver::{ControlError, StuckReason};
use drivebus::control::Blocker;
use drivebus::modbus::{ModbusLink, Table, UnitId};
use drivebus::testing::{MemoryBus, Request};
use drivebus::units::{Milliseconds, Percent};
use drivebus::{Error, ValueError};
use lafert_smartris::pdo::{Rpdo1, Tpdo1};
use lafert_smartris::types::{
    Controlword, DriveDigitalInputs, DrivePhysicalOutputs, ErrorCode, ModesOfOperation,
    MotionProfileType, SafetyFsmMode, Statusword, StoOptionCode, StoppingMode, TorqueProfileType,
};
use lafert_smartris::Smartris;

fn modbus(registers: &[(Table, u16, u16)]) -> Smartris<ModbusLink<MemoryBus>> {
    let mut bus = MemoryBus::new();
    for &(table, address, value) in registers {
        bus.set_register(table, address, value);
    }
    Smartris::modbus(bus, UnitId(1))
}

fn canopen(objects: &[(u16, u8, &[u8])]) -> Smartris<drivebus::canopen::CanOpenLink<MemoryBus>> {
    let mut bus = MemoryBus::new();
    for &(index, subindex, bytes) in objects {
        bus.set_object(index, subindex, bytes);
    }
    Smartris::canopen(bus, NodeId(1))
}

#[test]
fn the_three_stopping_mode_registers_are_signed_with_the_values_of_section_4_11() {
    // Guide 2745-2761: -1 … -5 besides 0 and 1; a drive set to -3 holds 0xFFFD.
    let mut drive = modbus(&[
        (Table::Holding, 0x0051, 0xFFFD),
        (Table::Holding, 0x0059, 0xFFFB),
        (Table::Holding, 0x005A, 0x0000),
    ]);
    assert_eq!(
        drive.move_to_standby_cw().read(),
        Ok(StoppingMode::IMMEDIATE_ZERO_BRAKE_LOCKED)
    );
    assert_eq!(drive.move_to_standby_cw().read_raw(), Ok(-3));
    assert_eq!(
        drive.move_to_standby_emergency().read(),
        Ok(StoppingMode::S_RAMP)
    );
    assert_eq!(drive.move_to_fault().read(), Ok(StoppingMode::COAST));
    drive
        .move_to_fault()
        .write(StoppingMode::OFF_BRAKE_LOCKED)
        .unwrap();
    // 2 and -6 are none of the documented modes: refused before anything is sent.
    assert!(matches!(
        drive.move_to_standby_cw().write_raw(2),
        Err(Error::Value(ValueError::OutOfRange { .. }))
    ));
    assert!(matches!(
        drive.move_to_standby_emergency().write_raw(-6),
        Err(Error::Value(ValueError::OutOfRange { .. }))
    ));
    let log = drive.into_link().into_bus().log().to_vec();
    let writes: Vec<&Request> = log
        .iter()
        .filter(|r| matches!(r, Request::Write { .. }))
        .collect();
    assert_eq!(
        writes,
        [&Request::Write {
            start: 0x005A,
            values: vec![0xFFFC]
        }]
    );
}

#[test]
fn speed_ramps_end_at_32000_ms() {
    // Guide line 1659: "their maximum values are 32000".
    let mut drive = modbus(&[(Table::Holding, 0x0040, 0), (Table::Holding, 0x0041, 0)]);
    drive.speed_ramp_up().write(Milliseconds(32_000.0)).unwrap();
    assert!(matches!(
        drive.speed_ramp_down().write(Milliseconds(32_001.0)),
        Err(Error::Value(ValueError::OutOfRange { .. }))
    ));
}

#[test]
fn safety_option_registers_read_their_documented_values() {
    // Guide 3651-3699: Safety FSM 0/1/2, STO option code 0/1.
    let mut drive = modbus(&[(Table::Holding, 0x005C, 1), (Table::Holding, 0x005D, 1)]);
    assert_eq!(drive.sto_opt_code().read(), Ok(StoOptionCode::BRAKE_CLOSED));
    assert_eq!(
        drive.safety_fsm_mode().read(),
        Ok(SafetyFsmMode::SAFETY_DIRECT)
    );
}

#[test]
fn motion_and_torque_profile_types_have_the_guides_values() {
    // Guide 5258/5264: 0 linear (default), -1 immediately; 5591/5593: 6088h -1 / 0.
    let mut drive = modbus(&[(Table::Holding, 0x0066, 0)]);
    assert_eq!(
        drive.motion_profile_type().read(),
        Ok(MotionProfileType::LINEAR_RAMP)
    );
    let mut drive = canopen(&[
        (0x6086, 0, &(-1i16).to_le_bytes()),
        (0x6088, 0, &(-1i16).to_le_bytes()),
    ]);
    assert_eq!(
        drive.motion_profile_type().read(),
        Ok(MotionProfileType::IMMEDIATELY)
    );
    assert_eq!(
        drive.torque_profile_type().read(),
        Ok(TorqueProfileType::IMMEDIATELY)
    );
}

#[test]
fn the_modes_of_operation_are_the_drives_own() {
    // Guide 4991-5005: 3, 4 and the manufacturer modes -1, -2; no vl, ip or cyclic modes.
    let mut drive = canopen(&[(0x6061, 0, &[0xFF]), (0x6060, 0, &[0])]);
    assert_eq!(
        drive.modes_of_operation_display().read(),
        Ok(ModesOfOperation::ANALOG_MODE)
    );
    assert!(
        ModesOfOperation::try_from(2i8).is_err(),
        "vl is not a Smartris mode"
    );
    drive
        .modes_of_operation()
        .write(ModesOfOperation::PROFILE_VELOCITY)
        .unwrap();
    let mut link = drive.into_link();
    assert_eq!(link.bus_mut().object(0x6060, 0), Some(&[3][..]));
}

#[test]
fn torque_limit_objects_are_percent_of_rated_current_from_1_to_100() {
    // Guide 2060, 2078: percent of rated current, range [1;100] %.
    let mut drive = canopen(&[(0x60E0, 0, &[50, 0]), (0x60E1, 0, &[100, 0])]);
    assert_eq!(
        drive.positive_torque_limit_value().read(),
        Ok(Percent(50.0))
    );
    assert!(matches!(
        drive.negative_torque_limit_value().write(Percent(0.0)),
        Err(Error::Value(ValueError::OutOfRange { .. }))
    ));
    drive
        .negative_torque_limit_value()
        .write(Percent(1.0))
        .unwrap();
}

#[test]
fn error_code_603f_decodes_through_table_2_and_the_guides_emcy_codes() {
    // Guide 4513: "The latest error message is always stored here in Error Code object (603Fh:0h)".
    let mut drive = canopen(&[(0x603F, 0, &0x7521u16.to_le_bytes())]);
    assert_eq!(
        drive.error_code().read(),
        Ok(ErrorCode::MODBUS_COMMUNICATION_LOST)
    );
    // Guide 2078 and 4534: codes the drive sends outside Table 2.
    assert!(ErrorCode::try_from(0x8B23u16).is_ok());
    assert!(ErrorCode::TORQUE_LIMIT_NOT_CORRECT
        .meaning()
        .unwrap()
        .contains("[1;100]"));
    assert_eq!(ErrorCode::CAN_STATE.raw(), 0x8170);
}

#[test]
fn the_error_history_has_15_entries() {
    // Guide 4515: "the error memory always saves the 15 most recent error messages".
    let mut drive = canopen(&[(0x1003, 15, &0x2340u32.to_le_bytes())]);
    assert_eq!(drive.standard_error_field(15).read_raw(), Ok(0x2340));
    assert!(matches!(
        drive.standard_error_field(16).read_raw(),
        Err(Error::Value(ValueError::OutOfRange { .. }))
    ));
}

#[test]
fn statusword_bit_14_is_safety_and_the_driver_reports_safe_torque_off() {
    // Guide 3671: "Bit 14 of the status word (CANOpen SAFETY bit) is set to '1' until STO is set".
    let status = 0x4240u16; // switch on disabled + SAFETY
    let mut drive = canopen(&[(0x6040, 0, &[0, 0]), (0x6041, 0, &status.to_le_bytes())]);
    assert!(drive
        .statusword()
        .read()
        .unwrap()
        .contains(Statusword::SAFETY));
    let deadline = Instant::now() + Duration::from_millis(200);
    match drive.enable_operation(deadline).unwrap_err() {
        ControlError::Stuck {
            reason: StuckReason::Blocked(Blocker::SafeTorqueOff),
            ..
        } => {}
        other => panic!("expected safe torque off, got {other}"),
    }
}

#[test]
fn pdo_1_carries_the_guides_default_mapping() {
    // Guide 4362/4374 and 4400/4411: 200h / 180h + node, 7 bytes each.
    assert_eq!(Rpdo1::cob_id(NodeId(1)), 0x201);
    assert_eq!(Tpdo1::cob_id(NodeId(1)), 0x181);
    let rpdo = Rpdo1 {
        controlword: Controlword::SWITCH_ON | Controlword::ENABLE_VOLTAGE | Controlword::QUICK_STOP,
        modes_of_operation: ModesOfOperation::PROFILE_VELOCITY,
        drive_physical_outputs: DrivePhysicalOutputs::SET_BRAKE,
    };
    assert_eq!(
        rpdo.encode().unwrap().as_bytes(),
        [0x07, 0x00, 0x03, 0x01, 0x00, 0x00, 0x00]
    );
    let tpdo = Tpdo1::decode(&[0x27, 0x40, 0x04, 0x02, 0x00, 0x00, 0x00]).unwrap();
    assert!(tpdo
        .statusword
        .contains(Statusword::OPERATION_ENABLED | Statusword::SAFETY));
    assert_eq!(
        tpdo.modes_of_operation_display,
        ModesOfOperation::PROFILE_TORQUE
    );
    assert!(tpdo
        .drive_digital_inputs
        .contains(DriveDigitalInputs::POSITIVE_LIMIT_SWITCH));
}

#[test]
fn the_simulated_drive_starts_at_the_guides_defaults() {
    let sim = drivesim::Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../descriptions/lafert-smartris"
    ))
    .unwrap();
    sim.with(|drive| {
        let store = drive.store();
        let value = |name: &str| store.int(store.id(name).unwrap()).unwrap();
        // Guide 4719: heartbeat 200 ms; 2068: torque limit 100 %; 5866/5880/5882: stopping mode 1;
        // 5258: linear ramp; 3642/3697: Safety FSM and STO option code 0; 3090/3092: jerk use 2.
        assert_eq!(value("producer_heartbeat_time"), 200);
        assert_eq!(value("positive_torque_limit_value"), 100);
        assert_eq!(value("negative_torque_limit_value"), 100);
        for name in [
            "move_to_standby_cw",
            "move_to_standby_emergency",
            "move_to_fault",
        ] {
            assert_eq!(value(name), 1, "{name}");
        }
        assert_eq!(value("motion_profile_type"), 0);
        assert_eq!(value("safety_fsm_mode"), 0);
        assert_eq!(value("sto_opt_code"), 0);
        assert_eq!(value("profile_jerk_use"), 2);
        assert_eq!(value("profile_jerk_count"), 2);
    });
}

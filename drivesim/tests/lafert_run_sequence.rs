//! The Lafert Smartris in Modbus mode: the manual's run sequence (§4.2.1, Table 3), the motor
//! ramp, and store / reset (§4.2), on the simulated drive with time advanced by hand.

use std::time::Duration;

use drivesim::{Drive, Refusal, Simulator};

const DRIVE_STATUS_STANDBY: i128 = 0x0002;
const DRIVE_STATUS_RUN_VELOCITY: i128 = 0x0001;
const DRIVE_STATUS_RUN_TORQUE: i128 = 0x0020;
const DRIVE_STATUS_STOP: i128 = 0x0004;
const DRIVE_STATUS_ALARM: i128 = 0x0010;

fn lafert() -> Simulator {
    Simulator::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../descriptions/lafert-smartris"
    ))
    .unwrap()
}

fn value(drive: &Drive, name: &str) -> i128 {
    let store = drive.store();
    store.int(store.id(name).unwrap()).unwrap()
}

fn write(drive: &mut Drive, name: &str, raw: i128) -> Result<(), Refusal> {
    let id = drive.store().id(name).unwrap();
    let data_type = drive.store().parameter(id).data_type;
    drive.write(id, &drivesim::raw::from_int(data_type, raw))
}

#[test]
fn run_sequence_ramps_the_motor_and_stops_it() {
    let sim = lafert();
    sim.preset("operation_mode", 2).unwrap();
    sim.preset("full_scale_velocity", 3000).unwrap();
    sim.with(|drive| {
        assert_eq!(value(drive, "drive_status"), DRIVE_STATUS_STANDBY, "T1");
        write(drive, "control_word", 0x0003).unwrap();
        assert_eq!(
            value(drive, "drive_status"),
            DRIVE_STATUS_RUN_VELOCITY,
            "T2"
        );
        write(drive, "speed_setpoint", 1500).unwrap();
        // Ramp: 2000 ms from 0 to 3000 rpm (defaults of 0x0040 and the preset full scale).
        drive.tick(Duration::from_millis(500));
        assert_eq!(value(drive, "velocity_average"), 750);
        drive.tick(Duration::from_millis(1000));
        assert_eq!(value(drive, "velocity_average"), 1500);
        write(drive, "control_word", 0x0001).unwrap();
        assert_eq!(value(drive, "drive_status"), DRIVE_STATUS_STOP, "T4");
        drive.tick(Duration::from_millis(1));
        assert_eq!(
            value(drive, "velocity_average"),
            0,
            "stop with maximum torque"
        );
        write(drive, "control_word", 0x0002).unwrap();
        assert_eq!(value(drive, "drive_status"), DRIVE_STATUS_STANDBY, "T6");
    });
}

#[test]
fn the_speed_setpoint_is_bounded_by_the_full_scale_velocity() {
    let sim = lafert();
    sim.preset("full_scale_velocity", 3000).unwrap();
    sim.with(|drive| {
        assert_eq!(write(drive, "speed_setpoint", 3001), Err(Refusal::TooHigh));
        assert_eq!(write(drive, "speed_setpoint", -3001), Err(Refusal::TooLow));
        write(drive, "speed_setpoint", -3000).unwrap();
    });
}

#[test]
fn control_word_outside_0_to_7_is_refused() {
    lafert().with(|drive| {
        assert_eq!(write(drive, "control_word", 8), Err(Refusal::TooHigh));
    });
}

#[test]
fn operation_mode_takes_effect_after_store_and_reset() {
    let sim = lafert();
    sim.preset("operation_mode", 2).unwrap();
    sim.with(|drive| {
        write(drive, "operation_mode", 1).unwrap();
        write(drive, "system_reset", 1).unwrap();
        assert_eq!(
            value(drive, "operation_mode"),
            2,
            "not stored: lost on reset"
        );
        write(drive, "operation_mode", 1).unwrap();
        write(drive, "store_eeprom", 1).unwrap();
        write(drive, "control_word", 0x0003).unwrap();
        assert_eq!(
            value(drive, "drive_status"),
            DRIVE_STATUS_RUN_VELOCITY,
            "still the boot mode"
        );
        write(drive, "system_reset", 1).unwrap();
        assert_eq!(
            value(drive, "drive_status"),
            DRIVE_STATUS_STANDBY,
            "reset boots to standby"
        );
        write(drive, "control_word", 0x0003).unwrap();
        assert_eq!(value(drive, "drive_status"), DRIVE_STATUS_RUN_TORQUE);
        write(drive, "restore_factory", 1).unwrap();
        write(drive, "system_reset", 1).unwrap();
        assert_eq!(
            value(drive, "operation_mode"),
            0,
            "factory: no default described"
        );
    });
}

#[test]
fn a_fault_stops_the_drive_until_reset() {
    let sim = lafert();
    sim.preset("operation_mode", 2).unwrap();
    sim.with(|drive| {
        write(drive, "control_word", 0x0003).unwrap();
        drive.inject_fault(0x3210); // DC link over-voltage
        assert_eq!(value(drive, "drive_status"), DRIVE_STATUS_ALARM, "T8");
        assert_eq!(value(drive, "error_code"), 0x3210);
        write(drive, "control_word", 0x0003).unwrap();
        assert_eq!(
            value(drive, "drive_status"),
            DRIVE_STATUS_ALARM,
            "no run from alarm"
        );
        write(drive, "system_reset", 1).unwrap();
        assert_eq!(value(drive, "drive_status"), DRIVE_STATUS_STANDBY, "T9");
    });
}

#[test]
fn with_the_ramp_disabled_the_speed_jumps_to_the_setpoint() {
    // RAMP ENABLE = 0: speed ramp disabled (line 1309), the `enable` of the setpoint's `[[ramp]]`.
    let sim = lafert();
    sim.preset("operation_mode", 2).unwrap();
    sim.preset("full_scale_velocity", 3000).unwrap();
    sim.preset("ramp_enable", 0).unwrap();
    sim.with(|drive| {
        write(drive, "control_word", 0x0003).unwrap();
        write(drive, "speed_setpoint", 1500).unwrap();
        drive.tick(Duration::from_millis(1));
        assert_eq!(value(drive, "velocity_average"), 1500);
    });
}

#[test]
fn the_canopen_target_velocity_ramps_with_the_profile_acceleration() {
    // Profile velocity mode: 60FFh reached with 6083h / 6084h (user guide line 5235), the
    // `[[ramp]]` of `target_velocity`; 2000 units per second up, 4000 down.
    let sim = lafert();
    sim.preset("profile_acceleration", 2000).unwrap();
    sim.preset("profile_deceleration", 4000).unwrap();
    sim.with(|drive| {
        for word in [0x06, 0x07, 0x0F] {
            write(drive, "controlword", word).unwrap();
        }
        write(drive, "target_velocity", 1000).unwrap();
        drive.tick(Duration::from_millis(250));
        assert_eq!(value(drive, "velocity_actual_value"), 500);
        drive.tick(Duration::from_millis(500));
        assert_eq!(value(drive, "velocity_actual_value"), 1000);
        write(drive, "target_velocity", 0).unwrap();
        drive.tick(Duration::from_millis(125));
        assert_eq!(value(drive, "velocity_actual_value"), 500);
    });
}

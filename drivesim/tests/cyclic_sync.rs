//! The simulated axis in the cyclic synchronous modes, on the example CiA 402 axis: in CSP each
//! target position is reached evenly over one interpolation period (60C2h), statusword bit 12
//! says the drive follows, bit 13 a following error; in CSV the position integrates the target
//! velocity. Time is advanced by hand.

use std::time::Duration;

use drivesim::Drive;

const AXIS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/csp_axis");

const FOLLOWS: u16 = 1 << 12;
const FOLLOWING_ERROR: u16 = 1 << 13;

fn drive() -> Drive {
    let checked = drivegen::check(std::path::Path::new(AXIS));
    let report = checked.render();
    Drive::new(checked.device.unwrap_or_else(|| panic!("{report}")))
}

fn set(drive: &mut Drive, name: &str, value: i64) {
    let id = drive.store().id(name).unwrap_or_else(|| panic!("{name}"));
    let width = drive.store().bytes(id).len();
    drive
        .write(id, &value.to_le_bytes()[..width])
        .unwrap_or_else(|e| panic!("{name} = {value}: {e:?}"));
}

fn get(drive: &Drive, name: &str) -> i128 {
    let id = drive.store().id(name).unwrap();
    drive.store().int(id).unwrap()
}

fn enabled(mode: i64) -> Drive {
    let mut drive = drive();
    set(&mut drive, "modes_of_operation", mode);
    for word in [0x06, 0x07, 0x0F] {
        set(&mut drive, "controlword", word);
    }
    drive
}

const MS: Duration = Duration::from_millis(1);

#[test]
fn csp_reaches_each_set_point_evenly_over_the_interpolation_period() {
    let mut drive = enabled(8);
    let status = get(&drive, "statusword") as u16;
    assert_eq!(status & 0x6F, 0x27, "operation enabled: {status:#06X}");
    assert_ne!(status & FOLLOWS, 0, "follows the command value");
    // The period is 4 ms: 400 units at 100 000 units/s.
    set(&mut drive, "target_position", 400);
    drive.tick(2 * MS);
    assert_eq!(get(&drive, "position_actual_value"), 200, "half way");
    assert_eq!(get(&drive, "velocity_actual_value"), 100_000);
    drive.tick(3 * MS);
    assert_eq!(get(&drive, "position_actual_value"), 400, "stands on it");
    assert_eq!(get(&drive, "velocity_actual_value"), 0);
    set(&mut drive, "target_position", 0);
    drive.tick(4 * MS);
    assert_eq!(get(&drive, "position_actual_value"), 0);
    assert_eq!(get(&drive, "statusword") as u16 & FOLLOWING_ERROR, 0);
}

#[test]
fn csp_reports_a_following_error_beyond_its_window_and_time_out() {
    let mut drive = enabled(8);
    drive.block_load(true);
    // 5 000 units away: beyond the 2 000 window for longer than 10 ms.
    set(&mut drive, "target_position", 5_000);
    drive.tick(4 * MS);
    drive.tick(4 * MS);
    assert_eq!(
        get(&drive, "statusword") as u16 & FOLLOWING_ERROR,
        0,
        "within time out"
    );
    drive.tick(8 * MS);
    assert_ne!(get(&drive, "statusword") as u16 & FOLLOWING_ERROR, 0);
}

#[test]
fn csv_integrates_the_target_velocity_and_nothing_moves_unless_enabled() {
    let mut drive = enabled(9);
    assert_ne!(get(&drive, "statusword") as u16 & FOLLOWS, 0);
    set(&mut drive, "target_velocity", 10_000);
    drive.tick(Duration::from_millis(100));
    let position = get(&drive, "position_actual_value");
    assert!((990..=1_010).contains(&position), "{position}");

    let mut idle = drive_disabled();
    set(&mut idle, "target_position", 400);
    idle.tick(4 * MS);
    assert_eq!(get(&idle, "position_actual_value"), 0);
}

fn drive_disabled() -> Drive {
    let mut drive = drive();
    set(&mut drive, "modes_of_operation", 8);
    drive
}

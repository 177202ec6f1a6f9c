//! The simulated positioning axis on the Kinco description (its objects found by CiA 402 index):
//! profile position with the set-point handshake, target reached and the following error,
//! homing onto the simulated switch with the home offset, and the stops as the option codes say.
//! Time is advanced by hand, so the trapezoid's and the ramps' timing is checked exactly.

use std::time::Duration;

use drivesim::Drive;

const KINCO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/kinco-fd");

const TARGET_REACHED: u16 = 1 << 10;
const BIT_12: u16 = 1 << 12;
const BIT_13: u16 = 1 << 13;
const BIT_15: u16 = 1 << 15;

fn drive() -> Drive {
    let checked = drivegen::check(std::path::Path::new(KINCO));
    let report = checked.render();
    Drive::new(checked.device.unwrap_or_else(|| panic!("{report}")))
}

/// Writes `value` to parameter `name` as a client does, in the parameter's width.
fn set(drive: &mut Drive, name: &str, value: i64) {
    let id = drive.store().id(name).unwrap_or_else(|| panic!("{name}"));
    let width = drive.store().bytes(id).len();
    let bytes = value.to_le_bytes();
    drive
        .write(id, &bytes[..width])
        .unwrap_or_else(|e| panic!("{name} = {value}: {e:?}"));
}

fn get(drive: &Drive, name: &str) -> i128 {
    let id = drive.store().id(name).unwrap();
    drive.store().int(id).unwrap()
}

fn status(drive: &Drive) -> u16 {
    get(drive, "statusword") as u16
}

/// Operation enabled in `mode`, with a profile of 10 000 units/s at 20 000 units/s².
fn enabled(mode: i64) -> Drive {
    let mut drive = drive();
    for word in [0x06, 0x07, 0x0F] {
        set(&mut drive, "controlword", word);
    }
    set(&mut drive, "modes_of_operation", mode);
    set(&mut drive, "profile_speed", 10_000);
    set(&mut drive, "profile_acceleration", 20_000);
    set(&mut drive, "profile_deceleration", 20_000);
    drive
}

/// Ticks in 10 ms steps until `done` or `limit` seconds; returns the seconds spent.
fn run_until(drive: &mut Drive, limit: f64, done: impl Fn(&Drive) -> bool) -> f64 {
    let mut spent = 0.0;
    while !done(drive) {
        assert!(
            spent < limit,
            "not done after {limit} s: status {:#06X}",
            status(drive)
        );
        drive.tick(Duration::from_millis(10));
        spent += 0.01;
    }
    spent
}

#[test]
fn a_profile_position_move_acknowledges_travels_the_trapezoid_and_reaches_its_target() {
    let mut drive = enabled(1);
    assert_ne!(status(&drive) & TARGET_REACHED, 0, "standing on its target");
    set(&mut drive, "target_position", 50_000);
    set(&mut drive, "controlword", 0x1F);
    let word = status(&drive);
    assert_eq!(word & (BIT_12 | TARGET_REACHED), BIT_12, "{word:#06X}");
    set(&mut drive, "controlword", 0x0F);
    assert_eq!(status(&drive) & BIT_12, 0, "acknowledge falls with bit 4");
    // 0.5 s up to 10 000/s (2 500), 0.5 s down (2 500), 45 000 at speed (4.5 s): 5.5 s.
    let spent = run_until(&mut drive, 10.0, |d| status(d) & TARGET_REACHED != 0);
    assert!((5.4..=5.6).contains(&spent), "{spent} s");
    assert_eq!(get(&drive, "position_actual"), 50_000);
    assert_eq!(get(&drive, "velocity_actual_value"), 0);

    set(&mut drive, "target_position", -2_000);
    set(&mut drive, "controlword", 0x4F);
    set(&mut drive, "controlword", 0x5F);
    run_until(&mut drive, 10.0, |d| status(d) & TARGET_REACHED != 0);
    assert_eq!(
        get(&drive, "position_actual"),
        48_000,
        "relative to the target"
    );
}

#[test]
fn a_set_point_during_a_move_follows_it_unless_changed_immediately() {
    let mut drive = enabled(1);
    set(&mut drive, "target_position", 10_000);
    set(&mut drive, "controlword", 0x1F);
    set(&mut drive, "controlword", 0x0F);
    drive.tick(Duration::from_millis(200));
    set(&mut drive, "target_position", 0);
    set(&mut drive, "controlword", 0x1F);
    drive.tick(Duration::from_millis(200));
    assert!(
        get(&drive, "position_actual") > 1_000,
        "still heading for 10 000"
    );
    set(&mut drive, "controlword", 0x0F);
    run_until(&mut drive, 10.0, |d| status(d) & TARGET_REACHED != 0);
    assert_eq!(
        get(&drive, "position_actual"),
        0,
        "then the buffered set-point"
    );

    set(&mut drive, "target_position", 10_000);
    set(&mut drive, "controlword", 0x1F);
    set(&mut drive, "controlword", 0x0F);
    drive.tick(Duration::from_millis(500));
    set(&mut drive, "target_position", 3_000);
    set(&mut drive, "controlword", 0x3F);
    run_until(&mut drive, 10.0, |d| status(d) & TARGET_REACHED != 0);
    assert_eq!(get(&drive, "position_actual"), 3_000, "replaced at once");
}

#[test]
fn a_blocked_load_ends_in_a_following_error_and_halt_stops_the_move() {
    let mut drive = enabled(1);
    set(&mut drive, "max_following_error", 1_000);
    drive.block_load(true);
    set(&mut drive, "target_position", 50_000);
    set(&mut drive, "controlword", 0x1F);
    run_until(&mut drive, 2.0, |d| status(d) & BIT_13 != 0);
    assert_eq!(get(&drive, "position_actual"), 0);
    drive.block_load(false);

    let mut drive = enabled(1);
    set(&mut drive, "target_position", 50_000);
    set(&mut drive, "controlword", 0x1F);
    drive.tick(Duration::from_secs(1));
    set(&mut drive, "controlword", 0x010F);
    let spent = run_until(&mut drive, 2.0, |d| status(d) & TARGET_REACHED != 0);
    assert!(spent <= 0.6, "stopped on the deceleration: {spent} s");
    assert!(get(&drive, "position_actual") < 50_000);
}

#[test]
fn homing_finds_the_switch_and_sets_the_home_offset() {
    let mut drive = enabled(6);
    drive.place_home_switch(Some(-4_000));
    set(&mut drive, "homing_method", 17);
    set(&mut drive, "homing_speed_switch", 4_000);
    set(&mut drive, "homing_acceleration", 40_000);
    set(&mut drive, "homing_offset", 250);
    set(&mut drive, "controlword", 0x1F);
    assert_eq!(status(&drive) & (TARGET_REACHED | BIT_12), 0, "homing");
    run_until(&mut drive, 3.0, |d| status(d) & BIT_12 != 0);
    let word = status(&drive);
    assert_eq!(
        word & (TARGET_REACHED | BIT_12 | BIT_13),
        TARGET_REACHED | BIT_12
    );
    assert_eq!(
        get(&drive, "position_actual"),
        -250,
        "home is minus the offset"
    );
    // Kinco declares `homing-attained-bit-15`: Reference_found shows from the homing attained.
    assert_ne!(word & BIT_15, 0, "reference found: {word:#06X}");

    // The switch stays where it is: homing again from elsewhere ends on the same place.
    set(&mut drive, "controlword", 0x0F);
    set(&mut drive, "modes_of_operation", 1);
    set(&mut drive, "target_position", 5_000);
    set(&mut drive, "controlword", 0x1F);
    run_until(&mut drive, 5.0, |d| status(d) & TARGET_REACHED != 0);
    assert_ne!(status(&drive) & BIT_15, 0, "kept in another mode");
    set(&mut drive, "controlword", 0x0F);
    set(&mut drive, "modes_of_operation", 6);
    set(&mut drive, "controlword", 0x1F);
    assert_eq!(status(&drive) & BIT_15, 0, "cleared by the new start");
    run_until(&mut drive, 5.0, |d| status(d) & BIT_12 != 0);
    assert_ne!(status(&drive) & BIT_15, 0);
    assert_eq!(get(&drive, "position_actual"), -250);
}

#[test]
fn homing_on_the_current_position_is_at_once_and_without_a_switch_fails() {
    let mut drive = enabled(6);
    set(&mut drive, "homing_method", 35);
    set(&mut drive, "homing_offset", -7);
    set(&mut drive, "controlword", 0x1F);
    assert_ne!(status(&drive) & BIT_12, 0);
    assert_eq!(get(&drive, "position_actual"), 7);

    let mut drive = enabled(6);
    drive.place_home_switch(None);
    set(&mut drive, "homing_method", 17);
    set(&mut drive, "controlword", 0x1F);
    assert_eq!(status(&drive) & (BIT_12 | BIT_13), BIT_13);
}

#[test]
fn profile_velocity_reports_target_reached_at_the_setpoint_and_speed_zero_at_rest() {
    let mut drive = enabled(3);
    assert_ne!(status(&drive) & BIT_12, 0, "speed zero");
    set(&mut drive, "target_velocity", 100_000);
    assert_eq!(status(&drive) & TARGET_REACHED, 0, "accelerating");
    run_until(&mut drive, 5.0, |d| status(d) & TARGET_REACHED != 0);
    assert_eq!(get(&drive, "velocity_actual_value"), 100_000);
    assert_eq!(status(&drive) & BIT_12, 0, "moving");
}

#[test]
fn profile_torque_drives_the_load_and_reports_target_reached() {
    let mut drive = enabled(4);
    set(&mut drive, "target_torque", 10);
    assert_ne!(
        status(&drive) & TARGET_REACHED,
        0,
        "no torque slope: at once"
    );
    drive.tick(Duration::from_secs(3));
    let speed = get(&drive, "velocity_actual_value");
    // 10 units × 1000 / 2 per second: settles at 5000.
    assert!((4_900..=5_000).contains(&speed), "{speed}");
    assert!(get(&drive, "position_actual") > 5_000, "the load moved");
    set(&mut drive, "controlword", 0x06);
    drive.tick(Duration::from_millis(10));
    assert_eq!(
        get(&drive, "velocity_actual_value"),
        0,
        "no torque out of enabled"
    );
}

// The stops (CiA 402-2 605Ah, 605Bh, 605Dh; Kinco manual section 8.13, lines 2128-2131): the
// quick stop on the slow down ramp (the profile deceleration) or the quick stop ramp (6085h),
// then switch on disabled (codes 1, 2) or quick stop active (5, 6); a halt on either ramp; a
// shutdown on the slow down ramp.

const STATE: u16 = 0x006F;
const QUICK_STOP_ACTIVE: u16 = 0x0007;
const SWITCH_ON_DISABLED: u16 = 0x0040;
const READY_TO_SWITCH_ON: u16 = 0x0021;

/// Moving at 10 000 units/s in profile position mode towards a far target, with a profile
/// deceleration of 10 000 units/s² (1 s to stop) and a quick stop deceleration of 50 000
/// (0.2 s); `setup` writes the option codes first.
fn moving(setup: &[(&str, i64)]) -> Drive {
    let mut drive = drive();
    for &(name, value) in setup {
        set(&mut drive, name, value);
    }
    for word in [0x06, 0x07, 0x0F] {
        set(&mut drive, "controlword", word);
    }
    set(&mut drive, "modes_of_operation", 1);
    set(&mut drive, "profile_speed", 10_000);
    set(&mut drive, "profile_acceleration", 100_000);
    set(&mut drive, "profile_deceleration", 10_000);
    set(&mut drive, "quick_stop_deceleration", 50_000);
    set(&mut drive, "target_position", 1_000_000);
    set(&mut drive, "controlword", 0x1F);
    set(&mut drive, "controlword", 0x0F);
    drive.tick(Duration::from_millis(500));
    assert_eq!(get(&drive, "velocity_actual_value"), 10_000, "at speed");
    drive
}

fn standing(drive: &Drive) -> bool {
    get(drive, "velocity_actual_value") == 0
}

#[test]
fn a_quick_stop_brakes_on_the_ramp_its_code_names_then_ends_where_the_code_says() {
    // Code 1: the slow down ramp, 1 s, braking in quick stop active, then switch on disabled.
    let mut drive = moving(&[("quick_stop_mode", 1)]);
    set(&mut drive, "controlword", 0x0B);
    assert_eq!(status(&drive) & STATE, QUICK_STOP_ACTIVE, "braking");
    let spent = run_until(&mut drive, 3.0, |d| status(d) & STATE == SWITCH_ON_DISABLED);
    assert!((0.95..=1.1).contains(&spent), "slow down ramp: {spent} s");

    // Code 2: the quick stop ramp, 0.2 s, then switch on disabled.
    let mut drive = moving(&[("quick_stop_mode", 2)]);
    set(&mut drive, "controlword", 0x0B);
    let spent = run_until(&mut drive, 3.0, |d| status(d) & STATE == SWITCH_ON_DISABLED);
    assert!((0.15..=0.3).contains(&spent), "quick stop ramp: {spent} s");

    // Code 6: the quick stop ramp, and the drive stays in quick stop active.
    let mut drive = moving(&[("quick_stop_mode", 6)]);
    set(&mut drive, "controlword", 0x0B);
    let spent = run_until(&mut drive, 3.0, standing);
    assert!((0.15..=0.3).contains(&spent), "quick stop ramp: {spent} s");
    drive.tick(Duration::from_millis(500));
    assert_eq!(status(&drive) & STATE, QUICK_STOP_ACTIVE, "stays");

    // Code 5: the slow down ramp, staying.
    let mut drive = moving(&[("quick_stop_mode", 5)]);
    set(&mut drive, "controlword", 0x0B);
    let spent = run_until(&mut drive, 3.0, standing);
    assert!((0.95..=1.1).contains(&spent), "slow down ramp: {spent} s");
    assert_eq!(status(&drive) & STATE, QUICK_STOP_ACTIVE, "stays");

    // Code 0: disable drive function, at once.
    let mut drive = moving(&[("quick_stop_mode", 0)]);
    set(&mut drive, "controlword", 0x0B);
    assert_eq!(status(&drive) & STATE, SWITCH_ON_DISABLED);
}

#[test]
fn a_halt_brakes_on_the_ramp_the_halt_option_code_names() {
    let mut drive = moving(&[("halt_mode", 1)]);
    set(&mut drive, "controlword", 0x010F);
    let spent = run_until(&mut drive, 3.0, |d| status(d) & TARGET_REACHED != 0);
    assert!((0.95..=1.1).contains(&spent), "slow down ramp: {spent} s");

    let mut drive = moving(&[("halt_mode", 2)]);
    set(&mut drive, "controlword", 0x010F);
    let spent = run_until(&mut drive, 3.0, |d| status(d) & TARGET_REACHED != 0);
    assert!((0.15..=0.3).contains(&spent), "quick stop ramp: {spent} s");
}

#[test]
fn a_shutdown_with_the_slow_down_code_ramps_the_velocity_mode_down() {
    // Profile velocity: the motor follows 60FFh on the Kinco ramp (per millisecond, line 1966).
    let run = |code: i64| {
        let mut drive = drive();
        set(&mut drive, "shutdown_stop_mode", code);
        for word in [0x06, 0x07, 0x0F] {
            set(&mut drive, "controlword", word);
        }
        set(&mut drive, "modes_of_operation", 3);
        set(&mut drive, "profile_acceleration", 100);
        set(&mut drive, "profile_deceleration", 10);
        set(&mut drive, "target_velocity", 5_000);
        drive.tick(Duration::from_millis(100));
        assert_eq!(get(&drive, "velocity_actual_value"), 5_000);
        set(&mut drive, "controlword", 0x06);
        assert_eq!(status(&drive) & STATE, READY_TO_SWITCH_ON);
        drive.tick(Duration::from_millis(100));
        get(&drive, "velocity_actual_value")
    };
    // 10 units/ms: 1 000 less after 100 ms.
    assert_eq!(run(1), 4_000, "slow down ramp");
    assert_eq!(run(0), 0, "disable drive function: at once");
}

/// The velocity of a profile position move to 20 000 on the S-curve fixture axis with motion
/// profile type `kind`, sampled every millisecond until target reached.
fn move_velocities(kind: i64) -> Vec<i128> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/s_curve_axis.toml"
    );
    let checked = drivegen::check(std::path::Path::new(path));
    let report = checked.render();
    let mut drive = Drive::new(checked.device.unwrap_or_else(|| panic!("{report}")));
    set(&mut drive, "motion_profile_type", kind);
    for word in [0x06, 0x07, 0x0F] {
        set(&mut drive, "controlword", word);
    }
    set(&mut drive, "modes_of_operation", 1);
    set(&mut drive, "profile_velocity", 10_000);
    set(&mut drive, "profile_acceleration", 20_000);
    set(&mut drive, "profile_deceleration", 20_000);
    set(&mut drive, "target_position", 20_000);
    set(&mut drive, "controlword", 0x1F);
    set(&mut drive, "controlword", 0x0F);
    let mut velocities = Vec::new();
    while status(&drive) & TARGET_REACHED == 0 {
        assert!(velocities.len() < 10_000, "no target reached");
        drive.tick(Duration::from_millis(1));
        velocities.push(get(&drive, "velocity_actual_value"));
    }
    assert_eq!(get(&drive, "position_actual_value"), 20_000);
    velocities
}

/// The largest change of the acceleration between two milliseconds, in units/s³, over the
/// first `len` samples.
fn largest_jerk(velocities: &[i128], len: usize) -> i128 {
    let accelerations: Vec<i128> = velocities[..len]
        .windows(2)
        .map(|w| (w[1] - w[0]) * 1_000)
        .collect();
    let jerks = accelerations
        .windows(2)
        .map(|w| (w[1] - w[0]).abs() * 1_000);
    jerks.max().unwrap_or(0)
}

#[test]
fn motion_profile_type_1_moves_on_an_s_curve_where_0_moves_on_the_trapezoid() {
    let trapezoid = move_velocities(0);
    let s_curve = move_velocities(1);
    // Over the start of the move, up to cruising (0.5 s on the trapezoid): the trapezoid's
    // acceleration jumps to 20 000/s² in one millisecond; the S-curve's rises by 2·a²/v =
    // 80 000/s³, a few units of rounding of the shown speed aside.
    let start = 800;
    assert!(largest_jerk(&trapezoid, start) >= 10_000_000);
    assert!(
        largest_jerk(&s_curve, start) <= 2_100_000,
        "{}",
        largest_jerk(&s_curve, start)
    );
    // Smoother, so later: one window (v / 2a = 0.25 s) more, on the same target.
    let later = s_curve.len() as i128 - trapezoid.len() as i128;
    assert!((200..=300).contains(&later), "{later} ms");
}

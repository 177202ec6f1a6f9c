//! Speeds at the wheel for the product models (section 3, lines 345-465): each model's gear
//! ratio as the manual prints it, and the wheel-speed setpoint through the simulated SWD.

mod support;

use drivebus::units::Rpm;
use drivebus::{Error, Ratio, ValueError};
use ezwheel_swd::{motor_speed, wheel_speed, Model};
use support::simulated_swd::start;

#[test]
fn each_model_has_the_printed_gear_ratio() {
    let exact = |n, d| Ratio::new(n, d);
    let expected = [
        (Model::SwdCore0x, exact(1, 1)),              // line 347
        (Model::SwdCore4x, exact(4, 1)),              // line 348
        (Model::SwdCore14x, exact(63 * 63, 17 * 17)), // line 363: (63/17)²
        (Model::SwdCore25x, exact(25, 1)),            // line 350
        (Model::SwdCore50x, exact(50, 1)),            // line 351
        (Model::SwdCore100x, exact(100, 1)),          // line 352
        (Model::Swd1254x, exact(62, 17)),             // line 413
        (Model::Swd12514x, exact(14, 1)),             // line 401
        (Model::Swd15014x, exact(3969, 289)),         // line 465: (63/17)²
        (Model::Swd15025x, exact(25, 1)),             // line 453
    ];
    for (model, ratio) in expected {
        assert_eq!(model.gear_ratio(), ratio, "{}", model.name());
    }
}

#[test]
fn the_standard_swd_150_turns_100_rpm_at_the_wheel_for_1372_rpm_at_the_motor() {
    // 14:1 exact (63/17)² = 13.733...: 100 rpm at the wheel (line 452) is 1373.4 rpm at the motor.
    let ratio = Model::Swd15014x.gear_ratio().unwrap();
    let motor = motor_speed(Rpm(100.0), ratio);
    assert!((motor.0 - 100.0 * 3969.0 / 289.0).abs() < 1e-9);
    let wheel = wheel_speed(motor, ratio).unwrap();
    assert!((wheel.0 - 100.0).abs() < 1e-9);
    assert_eq!(wheel_speed(Rpm(1.0), Ratio::ZERO), None);
}

#[test]
fn the_wheel_speed_setpoint_goes_through_the_models_ratio() {
    let (drive, _node) = start();
    let mut drive = drive.with_model(Model::SwdCore4x);
    drive.set_wheel_speed(Rpm(100.0)).unwrap();
    // 6042h carries rpm at the motor (vl dimension factor 1/1 by default): 4 × 100.
    assert_eq!(drive.vl_target_velocity().read_raw().unwrap(), 400);
    assert_eq!(drive.wheel_speed_setpoint().unwrap(), Rpm(100.0));
}

#[test]
fn without_a_model_the_wheel_speed_is_refused() {
    let (mut drive, _node) = start();
    assert_eq!(
        drive.set_wheel_speed(Rpm(10.0)),
        Err(Error::Value(ValueError::BadScale {
            parameter: "gear_ratio"
        }))
    );
    assert_eq!(drive.vl_target_velocity().read_raw().unwrap(), 0);
}

#[test]
fn the_measured_wheel_speed_is_the_vl_actual_value_through_the_ratio() {
    use std::time::{Duration, Instant};
    let (drive, _node) = start();
    let mut drive = drive.with_model(Model::SwdCore4x);
    assert_eq!(drive.wheel_speed_actual().unwrap(), Rpm(0.0));
    let deadline = Instant::now() + Duration::from_secs(3);
    drive.start_velocity_mode(deadline).unwrap();
    drive.set_wheel_speed(Rpm(25.0)).unwrap();
    // The simulated motor reaches 100 rpm at the motor along the vl ramp (500 rpm / s).
    let wheel = loop {
        let wheel = drive.wheel_speed_actual().unwrap();
        if wheel == Rpm(25.0) || Instant::now() > deadline {
            break wheel;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    assert_eq!(wheel, Rpm(25.0));
    // 6044h itself is rpm at the motor: 4 × 25.
    assert_eq!(drive.vl_velocity_actual_value().read_raw().unwrap(), 100);
}

#[test]
fn without_a_model_the_measured_wheel_speed_is_refused() {
    let (mut drive, _node) = start();
    assert_eq!(
        drive.wheel_speed_actual(),
        Err(Error::Value(ValueError::BadScale {
            parameter: "gear_ratio"
        }))
    );
}

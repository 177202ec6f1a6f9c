//! The manual's command sequences (section 10.5 over Modbus, section 11.5 over CANopen; manual
//! 003_8cc8f7f4f05b8633.txt), shared by the Modbus and SDO frame tests: each sequence is the same
//! writes through the generated API, whichever link the drive has. Macros rather than generic
//! functions, because each accessor's bounds depend on the link's protocol.

use drivebus::units::Rpm;

/// Bytes printed as hex pairs (`"01 06 31 00"`).
pub fn hex(printed: &str) -> Vec<u8> {
    printed
        .split_whitespace()
        .map(|pair| u8::from_str_radix(pair, 16).unwrap())
        .collect()
}

/// 0x00085555 DEC, the manual's "200 rpm" (lines 2474, 2495, 2505, 3257, 3267): 199.99988 rpm at
/// encoder resolution 10000. 200 rpm itself is 546133.33 DEC, which the API refuses to round.
pub fn rpm_200_as_printed() -> Rpm {
    Rpm(f64::from(0x0008_5555u32) * 1875.0 / (512.0 * 10_000.0))
}

/// Homing (lines 2492-2497 and 3254-3259): enable, mode 6, method 33, switch speed "200 rpm",
/// zero speed 150 rpm, start.
macro_rules! homing {
    ($drive:expr) => {{
        let drive = &mut $drive;
        drive.controlword().write_raw(0x0F).unwrap();
        drive
            .modes_of_operation()
            .write(kinco_fd::types::ModesOfOperation::HOMING)
            .unwrap();
        drive
            .homing_method()
            .write(kinco_fd::types::HomingMethod::METHOD33)
            .unwrap();
        drive
            .homing_speed_switch()
            .write(manual::rpm_200_as_printed())
            .unwrap();
        drive
            .homing_speed_zero()
            .write(drivebus::units::Rpm(150.0))
            .unwrap();
        drive.controlword().write_raw(0x1F).unwrap();
    }};
}
pub(crate) use homing;

/// The position move of lines 2504-2512 and 3266-3273: 50000 increments at profile speed
/// "200 rpm", then controlwords 2F, 3F, 4F, 5F.
macro_rules! position_move {
    ($drive:expr) => {{
        let drive = &mut $drive;
        drive
            .target_position()
            .write(drivebus::units::Increments(50_000.0))
            .unwrap();
        drive
            .profile_speed()
            .write(manual::rpm_200_as_printed())
            .unwrap();
        for command in [0x2F, 0x3F, 0x4F, 0x5F] {
            drive.controlword().write_raw(command).unwrap();
        }
    }};
}
pub(crate) use position_move;

/// Speed mode (lines 2485-2487, 2518-2520 and 3278-3281): mode 3, the target speed, enable.
macro_rules! speed_mode {
    ($drive:expr, $speed:expr) => {{
        let drive = &mut $drive;
        drive
            .modes_of_operation()
            .write(kinco_fd::types::ModesOfOperation::VELOCITY)
            .unwrap();
        drive.target_velocity().write($speed).unwrap();
        drive.controlword().write_raw(0x0F).unwrap();
    }};
}
pub(crate) use speed_mode;

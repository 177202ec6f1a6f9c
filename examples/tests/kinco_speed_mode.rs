//! The Kinco speed-mode example runs end to end over Modbus TCP, CANopen and Kinco RS-232 on its
//! simulators, and the motor reaches the commanded 150 rpm on all three.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The example binary `cargo test` builds next to the test binaries.
fn example() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().and_then(Path::parent).unwrap();
    profile_dir.join("examples").join("kinco_speed_mode")
}

#[test]
fn speed_mode_reaches_150_rpm_over_all_three_protocols() {
    let output = Command::new(example()).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert_eq!(
        stdout
            .matches("target speed   150 rpm (409600 DEC)")
            .count(),
        3,
        "{stdout}"
    );
    assert_eq!(
        stdout.matches("actual speed   150 rpm").count(),
        3,
        "{stdout}"
    );
    assert_eq!(stdout.matches("OPERATION_ENABLED").count(), 3, "{stdout}");
}

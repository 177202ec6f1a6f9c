//! The Lenze smd example runs end to end on its embedded simulator: the configuration comes from
//! #50, the serial speed beyond C11 is refused naming the bound, the status block decodes, the
//! started drive accelerates to 41.2 Hz (ACCEL, then RUN) and Stop ends the output, the speed
//! written inside the unlock guard reads back after the lock, and a command after the lock is
//! refused as the drive would refuse it (exception 01), by the handle before sending (typed
//! `Locked`).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The example binary `cargo test` builds next to the test binaries.
fn example() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().and_then(Path::parent).unwrap();
    profile_dir.join("examples").join("lenze_smd")
}

#[test]
fn lenze_smd_runs_on_its_simulated_drive() {
    let output = Command::new(example()).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "lenze_smd failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    for expected in [
        "configuration      Known(Pc507)",
        "drive family       smd",
        "control source     c40_modbus",
        "of maximum_output_frequency",
        "NO FAULT",
        "locked             serial speed 41.2 Hz",
        "start after lock   start: the drive is locked (exception 0x01)",
    ] {
        assert!(
            stdout.contains(expected),
            "missing {expected:?} in:\n{stdout}"
        );
    }
    // The status rows: command, actual, load, status, fault.
    let rows: Vec<Vec<&str>> = stdout
        .lines()
        .filter(|l| l.ends_with("NO FAULT"))
        .map(|l| l.split_whitespace().collect())
        .collect();
    let row = |command: &str, actual: &str, status: &str| {
        rows.iter()
            .any(|r| r[0] == command && r[2] == actual && r[6] == status)
    };
    assert!(row("41.2", "41.2", "run"), "at speed:\n{stdout}");
    assert!(
        rows.iter().any(|r| r[6] == "accel" && r[2] != "41.2"),
        "accelerating:\n{stdout}"
    );
    assert!(row("0.0", "0.0", "stop"), "stopped:\n{stdout}");
}

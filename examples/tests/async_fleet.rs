//! The async fleet example runs its four simulated drives at once for two seconds: the output names
//! the four, shows them turning, and ends with every drive stopped.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The example binary `cargo test` builds next to the test binaries.
fn example() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().and_then(Path::parent).unwrap();
    profile_dir.join("examples").join("async_fleet")
}

#[test]
fn four_drives_run_at_once_and_all_stop() {
    let output = Command::new(example())
        .args(["--seconds", "2"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "async_fleet failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let names = ["lafert-smartris", "lenze-smd", "ezwheel-swd", "kinco-fd"];
    let lines: Vec<&str> = stdout.lines().collect();
    let header = lines.first().copied().unwrap_or_default();
    for name in names {
        assert!(header.contains(name), "{name} has no column:\n{stdout}");
    }
    // A line per 500 ms with each drive's value and setpoint (read from the drive) in its unit.
    let rows = &lines[1..lines.len().saturating_sub(names.len())];
    assert_eq!(rows.len(), 4, "{stdout}");
    let last = rows.last().copied().unwrap_or_default();
    for value in [
        "(set 1500 rpm)",
        "(set 20.0 Hz)",
        "(set 298 rpm)",
        "(set 150 rpm)",
    ] {
        assert!(last.contains(value), "missing {value:?} in {last:?}");
    }
    // The four last lines: each drive stopped, in column order.
    let ends = &lines[lines.len() - names.len()..];
    for (name, line) in names.iter().zip(ends) {
        assert!(
            line.starts_with(name) && line.contains("stopped: "),
            "{name} did not stop:\n{stdout}"
        );
        assert!(
            line.contains("setpoint 0 rpm") || line.contains("locked"),
            "{line}"
        );
    }
}

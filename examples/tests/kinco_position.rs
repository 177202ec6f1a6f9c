//! The Kinco position example homes the simulated drive and reaches each of its three positions
//! within the position window.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The example binary `cargo test` builds next to the test binaries.
fn example() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().and_then(Path::parent).unwrap();
    profile_dir.join("examples").join("kinco_position")
}

#[test]
fn homes_and_reaches_three_positions() {
    let output = Command::new(example()).output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        stdout.contains("homed (method 17, offset 1000 inc): position -1000 inc"),
        "{stdout}"
    );
    for target in ["50000", "-20000", "120000"] {
        let line = format!("moved to {target:>8} inc: position {target:>8} inc, error 0 inc");
        assert!(stdout.contains(&line), "{line}\n{stdout}");
    }
}

//! The ez-Wheel SWD quick-start example runs end to end on its embedded simulator: safety
//! frames, NMT operational, velocity mode, the motor at 298 rpm and the wheel at 298 / 13.734.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The example binary `cargo test` builds next to the test binaries.
fn example() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().and_then(Path::parent).unwrap();
    profile_dir.join("examples").join("swd_quickstart")
}

#[test]
fn the_swd_quick_start_reaches_the_speed_and_stops() {
    let output = Command::new(example()).output().expect("the example runs");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    for line in [
        "safety             SRDO 1 invalid, signature 0xbabd, valid",
        "heartbeat          Operational",
        "state              Some(OperationEnabled)",
        "mode               velocity",
        "motor speed        298 rpm",
        "wheel speed        21.7 rpm (SWD 150, ratio 13.734)",
        "state              Some(SwitchOnDisabled)",
    ] {
        assert!(stdout.contains(line), "missing {line:?} in:\n{stdout}");
    }
}

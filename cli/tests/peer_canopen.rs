//! python canopen 2.4.1 (RemoteNode SDO, BaseNode402) as an independent CANopen master of the
//! simulator, reached through a candump stdio relay (`tests/peers/canopen_master.py`). A missing
//! peer fails the test: run `tests/peers/setup.sh`.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use peer_support::{python, workspace_root};

#[test]
fn python_canopen_drives_the_simulated_lafert_to_operation_enabled() {
    let mut child = Command::new(python())
        .arg(workspace_root().join("tests/peers/canopen_master.py"))
        .arg(env!("CARGO_BIN_EXE_drivegen"))
        .arg(workspace_root().join("descriptions/lafert-smartris"))
        .arg("1")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start python ({e}); run tests/peers/setup.sh"));
    let deadline = Instant::now() + Duration::from_secs(60);
    while child.try_wait().unwrap().is_none() {
        if Instant::now() > deadline {
            child.kill().unwrap();
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let output = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success() && stdout.trim_end().ends_with("ok"),
        "python canopen master failed ({}):\n{stdout}\n{}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
}

//! python canopen 2.4.1 (RemoteNode SDO, BaseNode402) as an independent CANopen master of the
//! simulator, reached through a candump stdio relay (`tests/peers/canopen_relay.py`). A missing
//! peer fails the test: run `tests/peers/setup.sh`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use peer_support::{python, workspace_root};

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

/// Runs a peer script with `args` (killed by its PID after a minute) and returns its output.
fn peer(script: &str, args: &[&Path]) -> Output {
    let mut child = Command::new(python())
        .arg(workspace_root().join("tests/peers").join(script))
        .args(args)
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
    child.wait_with_output().unwrap()
}

/// The last line of a peer's stdout, asserting it exited 0 with a line starting `ok`.
fn passed(what: &str, output: &Output) -> String {
    let stdout = String::from_utf8_lossy(&output.stdout);
    let last = stdout
        .trim_end()
        .lines()
        .last()
        .unwrap_or_default()
        .to_owned();
    assert!(
        output.status.success() && last.starts_with("ok"),
        "{what} failed ({}):\n{stdout}\n{}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    last
}

#[test]
fn python_canopen_drives_the_simulated_lafert_to_operation_enabled() {
    let lafert = workspace_root().join("descriptions/lafert-smartris");
    let output = peer(
        "canopen_master.py",
        &[Path::new(BIN), &lafert, Path::new("1")],
    );
    passed("python canopen master", &output);
}

/// Issue 34: python canopen's `LssMaster` inquires the simulated SWD's node id and identity,
/// selects it by its LSS address, configures node id 5, stores and resets it; the node boots up
/// as 5 and answers an SDO upload there.
#[test]
fn python_canopen_lss_master_gives_the_simulated_swd_node_id_5() {
    let swd = workspace_root().join("descriptions/ezwheel-swd");
    let output = peer("lss_master.py", &[Path::new(BIN), &swd]);
    let shown = passed("python canopen LSS master", &output);
    assert_eq!(shown, "ok");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("booted as node 5, 1018h sub 1 = 0x515"),
        "{stdout}"
    );
}

/// The shipped descriptions with a CANopen side.
fn canopen_descriptions() -> Vec<PathBuf> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(workspace_root().join("descriptions"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("device.toml").is_file())
        .filter(|p| {
            let checked = drivegen::check(p);
            checked.device.is_some_and(|d| d.canopen.is_some())
        })
        .collect();
    found.sort();
    found
}

#[test]
fn python_canopen_boots_every_canopen_description_through_its_exported_eds() {
    let descriptions = canopen_descriptions();
    assert!(
        descriptions.len() >= 3,
        "Lafert, SWD, Kinco: {descriptions:?}"
    );
    let scratch = std::env::temp_dir().join(format!("drivegen-boot-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    for description in &descriptions {
        let name = description.file_name().unwrap().to_string_lossy();
        let eds = scratch.join(format!("{name}.eds"));
        let export = Command::new(BIN)
            .args(["eds", "export"])
            .arg(description)
            .arg("-o")
            .arg(&eds)
            .output()
            .unwrap();
        assert!(export.status.success(), "{name}: eds export failed");
        let output = peer(
            "eds_boot_master.py",
            &[Path::new(BIN), description, &eds, Path::new("7")],
        );
        let shown = passed(&format!("{name}: boot through the EDS"), &output);
        assert!(shown.contains("NMT OPERATIONAL"), "{name}: {shown}");
        assert!(
            shown.contains("OPERATION ENABLED -> SWITCH ON DISABLED"),
            "{name}: every shipped CANopen drive is a CiA 402 drive: {shown}"
        );
    }
    let _ = std::fs::remove_dir_all(&scratch);
}

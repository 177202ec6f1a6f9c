//! A python canopen 2.4.1 script as an independent master of the simulated Kinco FD, with the
//! object dictionary of the EDS `drivegen::eds::export` writes from the Kinco description. The
//! simulated node runs here on a candump stream over the script's stdio; the script ends by
//! itself and is reaped. A missing peer fails the test (run `tests/peers/setup.sh`).

use std::process::{Command, Stdio};

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::NodeId;
use drivesim::canopen::{Node, NodeConfig};
use peer_support::{python, workspace_root, SETUP_HINT};

/// Runs `tests/peers/<script>` (workspace root) against simulated node 1 and fails the test,
/// naming `master`, unless the script succeeds.
pub fn python_master_passes(script: &str, master: &str) {
    let description = workspace_root().join("descriptions/kinco-fd");
    let checked = drivegen::check(&description);
    let device = checked.device.expect("the Kinco description checks");
    let dir = std::env::temp_dir().join(format!("kinco-fd-{script}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let eds = dir.join("kinco-fd.eds");
    std::fs::write(&eds, drivegen::eds::export(&device)).unwrap();

    let mut child = Command::new(python())
        .arg(workspace_root().join("tests/peers").join(script))
        .arg(&eds)
        .arg("1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start python ({e}); {SETUP_HINT}"));
    let mut bus = CandumpBus::from_child(&mut child).unwrap();
    let sim = drivesim::Simulator::load(&description).unwrap();
    let node = std::thread::spawn(move || {
        let config = NodeConfig {
            node: NodeId(1),
            heartbeat: None,
        };
        // Runs until the script's stdout closes.
        let _ = Node::new(sim.clone(), config, sim.variant()).run(&mut bus);
    });
    let output = child.wait_with_output().unwrap();
    node.join().unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        output.status.success(),
        "{master} failed ({}):\n{}\n{SETUP_HINT}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
}

//! python canopen 2.4.1's `BaseNode402` as an independent CiA 402 master of the simulated Kinco FD
//! (issue 32 item 5), with the object dictionary of the EDS `drivegen::eds::export` writes from
//! the Kinco description (tests/peers/kinco_motion_master.py at the workspace root): operation
//! enabled, `homing()`, a profile position move by SDO to 50,000 increments, target reached and
//! the actual position within the position window. The simulated node runs here on a candump
//! stream over the script's stdio; the script ends by itself and is reaped. A missing peer fails
//! the test (run `tests/peers/setup.sh`).

use std::process::{Command, Stdio};

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::NodeId;
use drivesim::canopen::{Node, NodeConfig};
use peer_support::{python, workspace_root, SETUP_HINT};

#[test]
fn python_canopen_base_node_402_homes_and_moves_the_simulated_kinco() {
    let description = workspace_root().join("descriptions/kinco-fd");
    let checked = drivegen::check(&description);
    let device = checked.device.expect("the Kinco description checks");
    let dir = std::env::temp_dir().join(format!("kinco-fd-motion-eds-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let eds = dir.join("kinco-fd.eds");
    std::fs::write(&eds, drivegen::eds::export(&device)).unwrap();

    let mut child = Command::new(python())
        .arg(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../tests/peers/kinco_motion_master.py"
        ))
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
        "python canopen BaseNode402 failed ({}):\n{}\n{SETUP_HINT}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
}

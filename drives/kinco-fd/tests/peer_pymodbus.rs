//! pymodbus 3.16.1 as an independent Modbus client of the simulated Kinco FD over Modbus TCP on
//! 127.0.0.1 (tests/peers/kinco_modbus_client.py): the manual's speed-mode registers and the
//! drive's refusals, including the FC 0x03 exception the description declares as 0x81. The
//! script ends by itself; a missing peer fails the test (run `tests/peers/setup.sh`).

use std::process::{Command, Stdio};

use drivebus::modbus::UnitId;
use peer_support::{python, workspace_root, SETUP_HINT};

#[test]
fn pymodbus_sends_the_speed_mode_registers_and_sees_the_refusals() {
    let sim = drivesim::Simulator::load(workspace_root().join("descriptions/kinco-fd")).unwrap();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let output = Command::new(python())
        .arg(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/peers/kinco_modbus_client.py"
        ))
        .args(["tcp", &server.local_addr().to_string()])
        .stdin(Stdio::null())
        .output()
        .unwrap_or_else(|e| panic!("cannot start python ({e}); {SETUP_HINT}"));
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success() && stdout.trim_end().ends_with("ok"),
        "pymodbus client failed ({}):\n{stdout}\n{stderr}\n{SETUP_HINT}",
        output.status
    );
}

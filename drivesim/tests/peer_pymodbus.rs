//! pymodbus 3.16.1 as an independent Modbus client of the simulator: TCP on loopback, and RTU
//! over a socat pty pair. Each test starts its peers and stops them by PID; a missing peer fails
//! the test (run `tests/peers/setup.sh`).

use std::process::{Command, Stdio};

use drivebus::modbus::client::{SerialConfig, SerialStream};
use drivebus::modbus::UnitId;
use drivesim::Simulator;
use peer_support::{pty_pair, python, workspace_root, SETUP_HINT};

fn lafert() -> Simulator {
    let sim = Simulator::load(workspace_root().join("descriptions/lafert-smartris")).unwrap();
    sim.preset("operation_mode", 2).unwrap();
    sim
}

/// Runs the pymodbus client script; asserts it printed "ok".
fn run_client(mode: &str, target: &str) {
    let output = Command::new(python())
        .arg(workspace_root().join("tests/peers/modbus_client.py"))
        .args([mode, target])
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

#[test]
fn pymodbus_runs_the_lafert_sequence_over_tcp() {
    let sim = lafert();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    run_client("tcp", &server.local_addr().to_string());
}

#[test]
fn pymodbus_runs_the_lafert_sequence_over_rtu_on_a_pty() {
    let pty = pty_pair();
    let (client_end, server_end) = (&pty.client, &pty.server);
    let sim = lafert();
    let mut stream =
        SerialStream::open(server_end.to_str().unwrap(), &SerialConfig::new(19_200)).unwrap();
    // The server thread ends with an I/O error once socat is gone, after the test.
    std::thread::spawn(move || drivesim::modbus::rtu::serve(&sim, &mut stream, UnitId(1)));
    run_client("rtu", client_end.to_str().unwrap());
}

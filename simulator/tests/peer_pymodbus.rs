//! pymodbus 3.16.1 as an independent Modbus client of the simulator: TCP on loopback, and RTU
//! over a socat pty pair. Each test starts its peers and stops them by PID; a missing peer fails
//! the test (run `tests/peers/setup.sh`).

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use drivebus::modbus::transport::{SerialConfig, SerialStream};
use drivebus::modbus::UnitId;
use drivesim::Simulator;

const SETUP_HINT: &str =
    "run `tests/peers/setup.sh` at the workspace root (socat, pymodbus in .venv)";

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn python() -> PathBuf {
    if let Some(python) = std::env::var_os("DRIVEGEN_PYTHON") {
        return python.into();
    }
    let venv = workspace_root().join(".venv/bin/python");
    if venv.exists() {
        venv
    } else {
        "python3".into()
    }
}

/// A child process killed by its PID and reaped when dropped.
struct Process(Child);

impl Drop for Process {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

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

/// A socat pty pair; returns the process and the two link paths.
fn pty_pair() -> (Process, PathBuf, PathBuf) {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "drivesim-pty-{}-{}",
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let (a, b) = (dir.join("client"), dir.join("server"));
    let child = Command::new("socat")
        .arg(format!("pty,raw,echo=0,link={}", a.display()))
        .arg(format!("pty,raw,echo=0,link={}", b.display()))
        .stdin(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start socat ({e}); {SETUP_HINT}"));
    let process = Process(child);
    let deadline = Instant::now() + Duration::from_secs(5);
    while !(a.exists() && b.exists()) {
        assert!(
            Instant::now() < deadline,
            "socat did not create the pty links"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    (process, a, b)
}

#[test]
fn pymodbus_runs_the_lafert_sequence_over_rtu_on_a_pty() {
    let (_socat, client_end, server_end) = pty_pair();
    let sim = lafert();
    let mut stream =
        SerialStream::open(server_end.to_str().unwrap(), &SerialConfig::new(19_200)).unwrap();
    // The server thread ends with an I/O error once socat is gone, after the test.
    std::thread::spawn(move || drivesim::modbus::rtu::serve(&sim, &mut stream, UnitId(1)));
    run_client("rtu", client_end.to_str().unwrap());
}

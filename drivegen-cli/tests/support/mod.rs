//! Running the `drivegen` binary from the tests, and reading what it printed.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, ExitStatus, Output, Stdio};
use std::time::{Duration, Instant};

/// The binary under test.
pub const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

/// Runs `drivegen args...` to completion.
pub fn drivegen(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

/// What it printed on stdout.
pub fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// What it printed on stderr.
pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// `drivegen sim DESCRIPTION --modbus-tcp 127.0.0.1:0 EXTRA...` started, and the address it
/// announced on its first line (the real port).
#[allow(dead_code)] // Not every test binary starts a simulator.
pub fn modbus_sim(description: &Path, extra: &[&str]) -> (Child, String) {
    let mut child = Command::new(BIN)
        .arg("sim")
        .arg(description)
        .args(["--modbus-tcp", "127.0.0.1:0"])
        .args(extra)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let addr = line
        .trim()
        .strip_prefix("listening on modbus-tcp ")
        .and_then(|rest| rest.split_whitespace().next())
        .unwrap_or_else(|| panic!("announcement: {line}"))
        .to_string();
    (child, addr)
}

/// How long a gateway gets to refuse its file or to stop on SIGTERM.
#[allow(dead_code)] // Only the gateway's tests wait so.
const GATEWAY_WAIT: Duration = Duration::from_secs(20);

/// `command` (a `drivegen gateway FILE` that must refuse its file) run to its end: its stderr.
/// A gateway that starts instead is killed and fails the test.
#[allow(dead_code)] // Only the gateway's tests.
pub fn refused(command: &mut Command) -> String {
    let mut child = command.stderr(Stdio::piped()).spawn().unwrap();
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > GATEWAY_WAIT {
            child.kill().unwrap();
            panic!("the gateway started instead of refusing its file");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let output = child.wait_with_output().unwrap();
    assert!(!output.status.success());
    stderr(&output)
}

/// Sends SIGTERM to `child` and waits for its exit (failing the test if it does not stop).
#[allow(dead_code)] // Only the gateway's tests.
pub fn terminate(child: &mut Child) -> ExitStatus {
    let pid = child.id().to_string();
    assert!(Command::new("kill")
        .args(["-TERM", &pid])
        .status()
        .unwrap()
        .success());
    let started = Instant::now();
    loop {
        if let Some(exit) = child.try_wait().unwrap() {
            return exit;
        }
        assert!(
            started.elapsed() < GATEWAY_WAIT,
            "the gateway did not stop on SIGTERM"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

//! Running the `drivegen` binary from the tests, and reading what it printed.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Output, Stdio};

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

//! Running the `drivegen` binary from the tests, and reading what it printed.

use std::process::{Command, Output};

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

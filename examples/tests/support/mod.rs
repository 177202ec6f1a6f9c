//! What the example tests share: running an example binary and reading what it printed.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Runs the example `name` (the binary `cargo test` builds next to the test binaries), checks
/// that it succeeded and returns what it printed on stdout.
#[allow(dead_code)] // each test binary uses `run` or `run_with`
pub fn run(name: &str) -> String {
    run_with(name, &[])
}

/// Runs the example `name` with the command-line arguments `args`, as [`run`] does.
#[allow(dead_code)]
pub fn run_with(name: &str, args: &[&str]) -> String {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().and_then(Path::parent).unwrap();
    let binary: PathBuf = profile_dir.join("examples").join(name);
    let output = Command::new(&binary)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("{}: {e}", binary.display()));
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    stdout
}

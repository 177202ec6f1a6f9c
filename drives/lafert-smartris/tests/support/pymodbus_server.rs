//! The pymodbus peer (tests/peers/modbus_server.py) as a child process, killed by its PID and
//! reaped when dropped; closing its stdin also ends it.
//!
//! Python comes from `DRIVEGEN_PYTHON`, else `.venv/bin/python` at the workspace root, else
//! `python3`. A missing peer fails the test with instructions; `tests/peers/setup.sh` installs it.

use std::io::{BufRead, BufReader};
use std::process::{Child, ChildStdin, Command, Stdio};

use peer_support::{python, workspace_root, SETUP_HINT};

/// The server process.
pub struct Server {
    child: Child,
    _stdin: Option<ChildStdin>,
    /// Where it listens, `127.0.0.1:<port>`.
    pub address: String,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts `modbus_server.py tcp` and reads the port it prints once listening.
#[allow(dead_code)] // not every test file starts it without options
pub fn start_server() -> Server {
    start_server_with(&[])
}

/// Starts `modbus_server.py tcp` with extra options (e.g. `--firmware 226`).
pub fn start_server_with(options: &[&str]) -> Server {
    start_mode("tcp", options)
}

/// Starts `modbus_server.py <mode>` (`tcp`, `rtu-over-tcp`) with extra options.
pub fn start_mode(mode: &str, options: &[&str]) -> Server {
    let mut args = vec![mode];
    args.extend_from_slice(options);
    start_script("modbus_server.py", &args)
}

/// Starts `pipelining_server.py` (pyModbusTCP: it answers requests sent back to back in one
/// write, which pymodbus 3.16.1 does not), a Lafert-like map for every unit id.
#[allow(dead_code)] // one test file pipelines
pub fn start_pipelining_server() -> Server {
    start_script("pipelining_server.py", &[])
}

/// Starts `tests/peers/<script> args...` and reads the port it prints once listening.
fn start_script(script: &str, args: &[&str]) -> Server {
    let python = python();
    let mut child = Command::new(&python)
        .arg(workspace_root().join("tests/peers").join(script))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {} ({e}); {SETUP_HINT}", python.display()));
    let stdin = child.stdin.take();
    let stdout = child.stdout.take().expect("piped stdout");
    let mut server = Server {
        child,
        _stdin: stdin,
        address: String::new(),
    };
    let mut line = String::new();
    BufReader::new(stdout)
        .read_line(&mut line)
        .expect("read the peer's stdout");
    let port = line.trim().strip_prefix("PORT ").unwrap_or_else(|| {
        panic!(
            "the pymodbus peer did not start (output {line:?}; is pymodbus 3.16.1 installed for {}?); {SETUP_HINT}",
            python.display()
        )
    });
    server.address = format!("127.0.0.1:{port}");
    server
}

//! Starting and stopping the python CANopen peers (see tests/peers/ at the workspace root).
#![allow(dead_code)] // Each test file uses part of this module.

use std::io::Read;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use drivebus::canopen::{CanBus, CanFrame};
pub use peer_support::{peers_dir, python};

/// Node id of the peers' LocalNode.
pub const NODE: u8 = 5;

const SETUP_HINT: &str = "the python CANopen peer is required: run tests/peers/setup-canopen.sh \
     (creates .venv with canopen==2.4.1 and python-can==4.6.1) or set DRIVEGEN_PYTHON";

/// Spawns a peer script with piped stdio; fails the test (never skips) if python is missing.
pub fn spawn_peer(script: &str, args: &[String]) -> Child {
    let python = python();
    Command::new(&python)
        .arg(peers_dir().join(script))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {}: {e}; {SETUP_HINT}", python.display()))
}

/// Kills a peer by its PID and reaps it; returns what it wrote to stderr.
pub fn stop(child: &mut Child) -> String {
    let _ = child.kill();
    let _ = child.wait();
    let mut stderr = String::new();
    if let Some(mut pipe) = child.stderr.take() {
        let _ = pipe.read_to_string(&mut stderr);
    }
    stderr
}

/// How long a peer may take to import python-canopen and boot on a loaded 2-core machine.
pub const STARTUP: Duration = Duration::from_secs(30);

/// Receives frames until one satisfies `want`, or fails after `timeout`.
pub fn expect_frame<B: CanBus>(
    bus: &mut B,
    timeout: Duration,
    what: &str,
    mut want: impl FnMut(&CanFrame) -> bool,
) -> Result<CanFrame, String> {
    let deadline = Instant::now() + timeout;
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return Err(format!("no {what} within {timeout:?}"));
        }
        match bus.recv(left) {
            Ok(Some(frame)) if want(&frame) => return Ok(frame),
            Ok(_) => {}
            Err(e) => return Err(format!("bus failed while waiting for {what}: {e}")),
        }
    }
}

pub fn is_boot_up(frame: &CanFrame) -> bool {
    frame.id() == 0x700 + u16::from(NODE) && frame.data() == [0]
}

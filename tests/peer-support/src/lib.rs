//! What the workspace's tests share, in one place: the workspace root, the python that has the
//! pinned peers, a process guard that kills by PID, socat pty pairs, an independent Modbus CRC,
//! the Kinco manual's telegram list, and a mosquitto broker.

pub mod kinco_telegrams;
pub mod modbus_crc;
pub mod mosquitto;

use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// What to run when a peer is missing; the tests fail with it rather than skip.
pub const SETUP_HINT: &str =
    "run `tests/peers/setup.sh` at the workspace root (socat, mosquitto, and .venv with the pinned pymodbus / canopen), or set DRIVEGEN_PYTHON";

/// The workspace root (this crate lives in `tests/peer-support`).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `tests/peers/`, where the python peer scripts live.
pub fn peers_dir() -> PathBuf {
    workspace_root().join("tests/peers")
}

/// `DRIVEGEN_PYTHON`, else the workspace's `.venv`, else `python3`.
pub fn python() -> PathBuf {
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

/// A child process killed by its PID and reaped when dropped; its stdin, if kept, closes then too.
pub struct Process {
    child: Child,
    _stdin: Option<ChildStdin>,
}

impl Process {
    /// Guards `child`, keeping its stdin open (peers that exit on end of input stay alive).
    pub fn new(mut child: Child) -> Self {
        let stdin = child.stdin.take();
        Self {
            child,
            _stdin: stdin,
        }
    }

    /// The guarded child, e.g. to take its stdout.
    pub fn child_mut(&mut self) -> &mut Child {
        &mut self.child
    }
}

impl Drop for Process {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A socat pty pair: the process and the directory of its links, both removed when dropped.
pub struct PtyPair {
    _socat: Process,
    dir: PathBuf,
    /// One end (give it to the client).
    pub client: PathBuf,
    /// The other end (give it to the server).
    pub server: PathBuf,
}

impl Drop for PtyPair {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Starts `socat pty,raw,echo=0,link=A pty,raw,echo=0,link=B` and waits for both links.
pub fn pty_pair() -> PtyPair {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "drivegen-pty-{}-{}",
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let (client, server) = (dir.join("client"), dir.join("server"));
    let child = Command::new("socat")
        .arg(format!("pty,raw,echo=0,link={}", client.display()))
        .arg(format!("pty,raw,echo=0,link={}", server.display()))
        .stdin(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start socat ({e}); {SETUP_HINT}"));
    let pair = PtyPair {
        _socat: Process::new(child),
        dir,
        client,
        server,
    };
    // socat creates the links asynchronously.
    let deadline = Instant::now() + Duration::from_secs(5);
    while !(pair.client.exists() && pair.server.exists()) {
        assert!(
            Instant::now() < deadline,
            "socat did not create the pty links"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    pair
}

/// Starts `python script args...` with its stdin kept open and waits for the `READY` line the
/// peer scripts print once they serve; panics with [`SETUP_HINT`] when it does not come.
pub fn ready_peer(script: &Path, args: &[&str]) -> Process {
    use std::io::{BufRead, BufReader};
    let python = python();
    let mut peer = Process::new(
        Command::new(&python)
            .arg(script)
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start {} ({e}); {SETUP_HINT}", python.display())),
    );
    let stdout = peer.child_mut().stdout.take().expect("piped stdout");
    let mut line = String::new();
    BufReader::new(stdout).read_line(&mut line).unwrap();
    assert_eq!(
        line.trim(),
        "READY",
        "{} did not start; {SETUP_HINT}",
        script.display()
    );
    peer
}

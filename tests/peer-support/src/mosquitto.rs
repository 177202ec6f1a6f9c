//! A mosquitto broker of a test's own (Debian's `mosquitto`, installed by
//! `tests/peers/setup.sh`) on 127.0.0.1, without persistence: a restart loses every retained
//! message. The gateway's MQTT tests and its benchmark start theirs through here.

use std::net::{TcpListener, TcpStream};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::{Process, SETUP_HINT};

/// A free TCP port on 127.0.0.1 (free when asked; the broker binds it right after).
pub fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0")
        .and_then(|listener| listener.local_addr())
        .expect("a loopback port")
        .port()
}

/// mosquitto listening on 127.0.0.1:`port` with `settings` (access rules, TLS files), its
/// configuration written into `dir`; returned once it accepts connections.
pub fn start(dir: &Path, port: u16, settings: &str) -> Process {
    let conf = dir.join("mosquitto.conf");
    let listener = format!("listener {port} 127.0.0.1\npersistence false\n");
    std::fs::write(&conf, listener + settings).expect("the test's folder is writable");
    // Debian puts the broker in /usr/sbin, which a user's PATH may not hold.
    let program = ["/usr/sbin/mosquitto", "/usr/local/sbin/mosquitto"]
        .into_iter()
        .find(|p| Path::new(p).exists())
        .unwrap_or("mosquitto");
    let child = Command::new(program)
        .arg("-c")
        .arg(&conf)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("mosquitto: {e}; {SETUP_HINT}"));
    let broker = Process::new(child);
    let started = Instant::now();
    while TcpStream::connect(("127.0.0.1", port)).is_err() {
        assert!(
            started.elapsed() < Duration::from_secs(20),
            "mosquitto did not listen on {port} (its settings: {settings})"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    broker
}

//! `drivegen watch --tui` under tmux against a simulated SWD the bus spawns: the screen shows the
//! parameter names, values and units; `space` freezes it and thaws it; `q` exits with status 0
//! and gives the terminal back (the alternate screen left, raw mode off: `stty` says `icanon`),
//! the `--plot` it drew alongside written.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

/// The answer timeout while the spawned simulator loads its description (see `commands.rs`).
const SIM_STARTUP_MS: &str = "10000";

/// A tmux server of this test's own (its own socket), killed when dropped.
struct Tmux {
    socket: String,
}

impl Tmux {
    fn run(&self, args: &[&str]) -> Output {
        Command::new("tmux")
            // Its own server, without the user's configuration.
            .args(["-L", &self.socket, "-f", "/dev/null"])
            .args(args)
            .output()
            .unwrap_or_else(|e| panic!("tmux: {e}; {}", peer_support::SETUP_HINT))
    }

    fn screen(&self) -> String {
        String::from_utf8_lossy(&self.run(&["capture-pane", "-p", "-t", "scope"]).stdout)
            .into_owned()
    }

    fn keys(&self, keys: &str) {
        assert!(self
            .run(&["send-keys", "-t", "scope", keys])
            .status
            .success());
    }

    /// The screen once `ready` says yes of it, within 30 s.
    fn wait_for(&self, what: &str, ready: impl Fn(&str) -> bool) -> String {
        let deadline = Instant::now() + Duration::from_secs(30);
        loop {
            let screen = self.screen();
            if ready(&screen) {
                return screen;
            }
            assert!(
                Instant::now() < deadline,
                "waited for {what}; the screen:\n{screen}"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    }
}

impl Drop for Tmux {
    fn drop(&mut self) {
        let _ = self.run(&["kill-server"]);
    }
}

/// The polls counted in the header (`polls=N`).
fn polls(screen: &str) -> u64 {
    let after = screen.split("polls=").nth(1).unwrap_or("");
    after
        .split_whitespace()
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or(0)
}

/// A script that starts the simulated SWD on node 4 with its stderr kept off the screen.
fn simulator(dir: &Path, swd: &str) -> PathBuf {
    let script = dir.join("sim.sh");
    std::fs::write(
        &script,
        format!("#!/bin/sh\nexec {BIN} sim {swd} --can candump:stdio --node-id 4 2>/dev/null\n"),
    )
    .unwrap();
    Command::new("chmod")
        .arg("+x")
        .arg(&script)
        .status()
        .unwrap();
    script
}

#[test]
fn the_scope_shows_names_and_units_pauses_and_quits_restoring_the_terminal() {
    let dir = std::env::temp_dir().join(format!("drivegen-tui-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let swd = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/ezwheel-swd");
    let swd = swd.to_str().unwrap();
    let sim = simulator(&dir, swd);
    let watch = format!(
        "{BIN} watch {swd} statusword position_actual_value --can candump:exec:{} --node-id 4 \
         --timeout-ms {SIM_STARTUP_MS} --interval-ms 100 --tui --plot {}; echo EXIT=$?; \
         stty -a | tr ' ;' '\\n\\n' | grep -x -- '-*icanon'; sleep 60",
        sim.display(),
        dir.join("scope.svg").display()
    );
    let tmux = Tmux {
        socket: format!("drivegen-tui-{}", std::process::id()),
    };
    let started = tmux.run(&[
        "new-session",
        "-d",
        "-s",
        "scope",
        "-x",
        "120",
        "-y",
        "40",
        &watch,
    ]);
    assert!(
        started.status.success(),
        "{}",
        String::from_utf8_lossy(&started.stderr)
    );

    let running = tmux.wait_for("three polls", |s| polls(s) >= 3);
    assert!(
        running.contains("statusword: switch_on_disabled"),
        "{running}"
    );
    assert!(
        running.contains("position_actual_value: 0 inc"),
        "{running}"
    );
    assert!(running.contains("running"), "{running}");
    let later = tmux.wait_for("more polls", |s| polls(s) > polls(&running));
    assert_ne!(running, later, "running, the screen moves");

    tmux.keys("Space");
    let paused = tmux.wait_for("the pause", |s| s.contains("PAUSED"));
    std::thread::sleep(Duration::from_millis(800));
    assert_eq!(tmux.screen(), paused, "paused, the screen holds still");

    tmux.keys("Space");
    let resumed = tmux.wait_for("the resume", |s| {
        s.contains("running") && polls(s) > polls(&paused)
    });
    assert!(!resumed.contains("PAUSED"));

    tmux.keys("q");
    let after = tmux.wait_for("the exit", |s| s.contains("icanon"));
    assert!(after.contains("EXIT=0"), "{after}");
    assert!(
        after.lines().any(|l| l.trim() == "icanon"),
        "raw mode is off: {after}"
    );
    assert!(
        !after.contains("polls="),
        "the alternate screen is left: {after}"
    );
    drop(tmux);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn the_scope_of_several_drives_is_refused_before_the_bus_is_opened() {
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    listener.set_nonblocking(true).unwrap();
    let can = format!("slcan:{}", listener.local_addr().unwrap());
    let swd = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/ezwheel-swd");
    let output = Command::new(BIN)
        .arg("watch")
        .arg(swd)
        .args([
            "statusword",
            "--tui",
            "--can",
            &can,
            "--node-id",
            "4",
            "--node-id",
            "5",
        ])
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("--tui shows one drive"), "{stderr}");
    match listener.accept() {
        Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {}
        other => panic!("the bus was opened: {other:?}"),
    }
}

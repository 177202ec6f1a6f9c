//! `drivegen read / write / watch --kinco-rs232` against `drivegen sim --kinco-rs232`, through a
//! real socat pty pair: both ends are the binary, as a user would run them.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use peer_support::{pty_pair, Process, PtyPair};

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/fixtures/kinco-rs232")
}

/// `drivegen sim` on the server end of the pty, once it announced itself.
fn sim(pty: &PtyPair, extra: &[&str]) -> Process {
    let fixture = fixture();
    let child = Command::new(BIN)
        .args(["sim", fixture.to_str().unwrap(), "--kinco-rs232"])
        .arg(&pty.server)
        .args(["--set", "encoder_resolution=10000"])
        .args(extra)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut process = Process::new(child);
    let mut line = String::new();
    BufReader::new(process.child_mut().stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    assert!(
        line.starts_with("listening on kinco-rs232 ") && line.contains("station 1"),
        "announcement: {line}"
    );
    process
}

fn drivegen(pty: &PtyPair, args: &[&str], extra: &[&str]) -> Output {
    let fixture = fixture();
    let (command, rest) = args.split_first().unwrap();
    Command::new(BIN)
        .arg(command)
        .arg(fixture)
        .args(rest)
        .arg("--kinco-rs232")
        .arg(&pty.client)
        .args(["--timeout-ms", "300"])
        .args(extra)
        .output()
        .unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn read_write_and_watch_over_rs232() {
    let pty = pty_pair();
    let _sim = sim(&pty, &[]);
    let write = drivegen(&pty, &["write", "target_position", "50000"], &[]);
    assert!(write.status.success(), "{}", text(&write.stderr));
    // The CLI takes run-time scaled values raw: 409600 DEC is 150 rpm (manual line 2364).
    let speed = drivegen(&pty, &["write", "target_speed", "raw:409600"], &[]);
    assert!(speed.status.success(), "{}", text(&speed.stderr));
    let read = drivegen(
        &pty,
        &[
            "read",
            "target_position",
            "target_speed",
            "encoder_resolution",
        ],
        &[],
    );
    assert!(read.status.success(), "{}", text(&read.stderr));
    let out = text(&read.stdout);
    assert!(out.contains("50000"), "{out}");
    assert!(out.contains("409600"), "{out}");
    assert!(out.contains("10000"), "{out}");
    let watch = drivegen(
        &pty,
        &[
            "watch",
            "target_position",
            "--count",
            "2",
            "--interval-ms",
            "10",
        ],
        &[],
    );
    assert!(watch.status.success(), "{}", text(&watch.stderr));
    let polls = text(&watch.stdout)
        .lines()
        .filter(|l| l.contains("50000"))
        .count();
    assert_eq!(polls, 2, "{}", text(&watch.stdout));
}

#[test]
fn a_loop_and_a_baud_rate_are_options_of_both_ends() {
    let pty = pty_pair();
    let _sim = sim(&pty, &["--rs232-loop", "--baud", "115200"]);
    let extra = ["--rs232-loop", "--baud", "115200"];
    let read = drivegen(&pty, &["read", "operation_mode"], &extra);
    assert!(read.status.success(), "{}", text(&read.stderr));
    // Without the loop option the echo arrives where the answer is due.
    let read = drivegen(&pty, &["read", "operation_mode"], &[]);
    assert!(!read.status.success());
    let err = text(&read.stderr);
    assert!(
        err.contains("operation_mode") && err.contains("0x6060:0"),
        "{err}"
    );
    assert!(
        err.contains("the request came back where the answer was due"),
        "{err}"
    );
}

#[test]
fn refusals_name_the_object_and_the_cause() {
    let pty = pty_pair();
    let _sim = sim(&pty, &[]);
    // Read-only over RS-232: refused by the CLI before anything is sent.
    let write = drivegen(&pty, &["write", "statusword", "6"], &[]);
    assert!(!write.status.success());
    assert!(
        text(&write.stderr).contains("read-only"),
        "{}",
        text(&write.stderr)
    );
    // Modbus only: no RS-232 address.
    let read = drivegen(&pty, &["read", "positioning_select"], &[]);
    assert!(!read.status.success());
    assert!(
        text(&read.stderr).contains("no Kinco RS-232 address"),
        "{}",
        text(&read.stderr)
    );
    // A station that does not answer.
    let read = drivegen(&pty, &["read", "statusword"], &["--node-id", "9"]);
    assert!(!read.status.success());
    let err = text(&read.stderr);
    assert!(
        err.contains("0x6041:0") && err.contains("no answer"),
        "{err}"
    );
}

//! `drivegen read / write / scan --can slcan:/dev/PATH` through a real pty pair, against an
//! emulated serial SLCAN adapter (Lawicel / CANable command set, `slcan_adapter`) bridged to
//! `drivegen sim`: the opening sequence with the description's bit rate, frames both ways,
//! adapter timestamps, line noise, and an adapter that refuses or stays silent.

mod slcan_adapter;

use std::path::PathBuf;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use peer_support::{pty_pair, PtyPair};
use slcan_adapter::{Adapter, Options};

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn swd() -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../descriptions/ezwheel-swd")
        .to_str()
        .unwrap()
        .to_owned()
}

fn adapter(pty: &PtyPair, options: Options) -> Adapter {
    slcan_adapter::start(BIN, &pty.server, &[&swd()], options)
}

fn drivegen(pty: &PtyPair, args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .args(["--can", &format!("slcan:{}", pty.client.display())])
        .args(["--timeout-ms", "500"])
        .output()
        .unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn ok(output: &Output) -> String {
    assert!(
        output.status.success(),
        "stdout: {}\nstderr: {}",
        text(&output.stdout),
        text(&output.stderr)
    );
    text(&output.stdout)
}

#[test]
fn read_and_write_by_name_through_a_serial_adapter_at_the_described_bit_rate() {
    let pty = pty_pair();
    let adapter = adapter(&pty, Options::default());
    let swd = swd();
    let read = ok(&drivegen(&pty, &["read", &swd, "node_id", "--json"]));
    assert!(read.contains("\"raw\":16"), "{read}");
    ok(&drivegen(
        &pty,
        &["write", &swd, "termination_resistor", "0"],
    ));
    let read = ok(&drivegen(
        &pty,
        &["read", &swd, "termination_resistor", "--json"],
    ));
    assert!(read.contains("\"raw\":0"), "{read}");
    let state = adapter.state.lock().unwrap();
    // Each run opens the adapter: close, the SWD's documented 1 Mbit/s (S8), open.
    assert_eq!(
        state.commands[..3],
        ["C", "S8", "O"],
        "{:?}",
        state.commands
    );
    assert!(state.to_bus >= 3 && state.to_pty >= 3, "{state:?}");
    // Only the first C (channel already closed) was refused.
    assert_eq!(state.refused, 1, "{:?}", state.commands);
}

#[test]
fn bitrate_option_sets_the_adapter_rate() {
    let pty = pty_pair();
    let adapter = adapter(&pty, Options::default());
    ok(&drivegen(
        &pty,
        &["read", &swd(), "node_id", "--bitrate", "250k"],
    ));
    let state = adapter.state.lock().unwrap();
    assert_eq!(
        state.commands[..3],
        ["C", "S5", "O"],
        "{:?}",
        state.commands
    );
}

#[test]
fn scan_finds_the_drive_through_timestamps_and_line_noise() {
    let pty = pty_pair();
    let options = Options {
        always_timestamp: true,
        garbage: true,
        ..Options::default()
    };
    let adapter = adapter(&pty, options);
    let swd = swd();
    let output = Command::new(BIN)
        .args(["scan", "--description", &swd])
        .args(["--can", &format!("slcan:{}", pty.client.display())])
        .output()
        .unwrap();
    let found = ok(&output);
    assert!(found.contains("node  16:"), "{found}");
    assert!(found.contains("ez-Wheel SWD"), "{found}");
    let read = ok(&drivegen(&pty, &["read", &swd, "node_id", "--json"]));
    assert!(read.contains("\"raw\":16"), "{read}");
    assert!(adapter.state.lock().unwrap().to_pty > 2);
}

#[test]
fn the_simulator_on_one_serial_adapter_answers_the_cli_on_another() {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let (sim_pty, cli_pty) = (pty_pair(), pty_pair());
    let [sim_side, cli_side] =
        slcan_adapter::pair(&sim_pty.server, &cli_pty.server, Options::default());
    let swd = swd();
    let spec = format!("slcan:{}", sim_pty.client.display());
    let child = Command::new(BIN)
        .args([
            "sim",
            &swd,
            "--can",
            &spec,
            "--node-id",
            "16",
            "--node-id",
            "17",
        ])
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut sim = peer_support::Process::new(child);
    let mut line = String::new();
    BufReader::new(sim.child_mut().stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    assert_eq!(
        line.trim(),
        format!("listening on canopen {spec} node 16,17")
    );
    let read = ok(&drivegen(&cli_pty, &["read", &swd, "node_id", "--json"]));
    assert!(read.contains("\"raw\":16"), "{read}");
    let found = ok(&Command::new(BIN)
        .args(["scan", "--description", &swd])
        .args(["--can", &format!("slcan:{}", cli_pty.client.display())])
        .output()
        .unwrap());
    assert!(
        found.contains("node  16:") && found.contains("node  17:"),
        "{found}"
    );
    // Both opened their adapter at the SWD's 1 Mbit/s.
    for side in [&sim_side, &cli_side] {
        let side = side.lock().unwrap();
        assert_eq!(side.commands[..3], ["C", "S8", "O"], "{:?}", side.commands);
    }
}

/// An adapter that opens properly, then sends nothing but line noise (a wrong serial speed
/// after a reset, a broken cable): the read ends with a timeout in bounded time, no hang, no
/// panic.
#[test]
fn line_noise_after_opening_ends_in_a_timeout_not_a_hang() {
    use std::fs::OpenOptions;
    use std::io::{Read, Write};
    let pty = pty_pair();
    let mut port = OpenOptions::new()
        .read(true)
        .write(true)
        .open(&pty.server)
        .unwrap();
    let mut writer = port.try_clone().unwrap();
    std::thread::spawn(move || {
        // Answer C, Sn and O, then noise: CRs, BELs, bytes of every value, long runs.
        let mut seen = 0;
        let mut byte = [0u8; 1];
        while seen < 3 && port.read(&mut byte).is_ok_and(|n| n == 1) {
            if byte[0] == b'\r' {
                seen += 1;
                let _ = writer.write_all(b"\r");
            }
        }
        let mut state = 0x2545_F491_u32;
        let started = Instant::now();
        while started.elapsed() < Duration::from_secs(4) {
            let chunk: Vec<u8> = (0..97)
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 17;
                    state ^= state << 5;
                    state as u8
                })
                .collect();
            if writer.write_all(&chunk).is_err() {
                return;
            }
            std::thread::sleep(Duration::from_millis(2));
        }
    });
    let started = Instant::now();
    let output = drivegen(&pty, &["read", &swd(), "node_id"]);
    let elapsed = started.elapsed();
    assert!(!output.status.success());
    let error = text(&output.stderr);
    assert!(
        error.contains("no answer") && error.contains("timeout"),
        "{error}"
    );
    assert!(elapsed < Duration::from_secs(3), "{elapsed:?}");
}

#[test]
fn decode_live_from_a_serial_adapter_with_its_timestamps() {
    let pty = pty_pair();
    let options = Options {
        always_timestamp: true,
        ..Options::default()
    };
    let swd = swd();
    // The simulator's boot-up and heartbeats are the traffic.
    let _adapter = slcan_adapter::start(
        BIN,
        &pty.server,
        &[&swd, "--set", "producer_heartbeat_time=20"],
        options,
    );
    let output = Command::new(BIN)
        .args([
            "decode",
            &swd,
            "--count",
            "3",
            "--idle-ms",
            "2000",
            "--json",
        ])
        .args(["--can", &format!("slcan:{}", pty.client.display())])
        .output()
        .unwrap();
    let lines = ok(&output);
    let lines: Vec<&str> = lines.lines().collect();
    assert_eq!(lines.len(), 3, "{lines:?}");
    for line in lines {
        assert!(line.contains("\"kind\":\"heartbeat\""), "{line}");
        assert!(
            line.contains("ms\",") && line.contains("\"node\":\"16\""),
            "{line}"
        );
    }
}

#[test]
fn a_refusing_or_silent_adapter_is_a_clear_error_in_bounded_time() {
    let pty = pty_pair();
    let _adapter = adapter(
        &pty,
        Options {
            refuse_bitrate: true,
            ..Options::default()
        },
    );
    let output = drivegen(&pty, &["read", &swd(), "node_id"]);
    assert!(!output.status.success());
    assert!(
        text(&output.stderr).contains("the SLCAN adapter refused its `S8` command (answered BEL)"),
        "{}",
        text(&output.stderr)
    );
    drop(_adapter);
    let pty = pty_pair();
    let _adapter = adapter(
        &pty,
        Options {
            silent: true,
            ..Options::default()
        },
    );
    let started = Instant::now();
    let output = drivegen(&pty, &["read", &swd(), "node_id"]);
    assert!(
        text(&output.stderr).contains("did not answer its `S8` command"),
        "{}",
        text(&output.stderr)
    );
    assert!(started.elapsed() < Duration::from_secs(5));
}

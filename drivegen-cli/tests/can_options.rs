//! `--can` on every command that takes it: the forms `--help` lists, `--bitrate`, and the typed
//! errors for a missing interface, a missing device, a silent adapter and a bad form.

use std::path::PathBuf;
use std::process::{Command, Output};

use peer_support::pty_pair;

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn swd() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../descriptions/ezwheel-swd")
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn help_lists_every_can_form_and_the_bitrate() {
    for command in ["read", "write", "watch", "scan", "sim"] {
        let output = run(&[command, "--help"]);
        let help = String::from_utf8_lossy(&output.stdout);
        for form in [
            "socketcan:IFACE",
            "slcan:/dev/PATH",
            "slcan:HOST:PORT",
            "--bitrate",
            "500k",
        ] {
            assert!(
                help.contains(form),
                "{command} --help lacks {form}:\n{help}"
            );
        }
        let candump = if command == "sim" {
            "candump:stdio"
        } else {
            "candump:exec:COMMAND"
        };
        assert!(help.contains(candump), "{command} --help lacks {candump}");
    }
}

#[test]
fn a_missing_interface_names_the_command_that_brings_it_up() {
    let swd = swd();
    let swd = swd.to_str().unwrap();
    for args in [
        &["read", swd, "node_id", "--can", "socketcan:nocan0"][..],
        &["write", swd, "node_id", "16", "--can", "socketcan:nocan0"],
        &["watch", swd, "node_id", "--can", "socketcan:nocan0"],
        &["scan", "--can", "socketcan:nocan0", "--description", swd],
        &["sim", swd, "--can", "socketcan:nocan0"],
    ] {
        let output = run(args);
        assert!(!output.status.success(), "{args:?}");
        // The SWD's documented default bit rate (2100h default 0: 1 Mbit/s) is in the hint.
        assert_eq!(
            stderr(&output).trim(),
            "error: no CAN interface nocan0; bring it up with `ip link set nocan0 up type can bitrate 1000000`",
            "{args:?}"
        );
    }
    let output = run(&[
        "read",
        swd,
        "node_id",
        "--can",
        "socketcan:nocan0",
        "--bitrate",
        "250k",
    ]);
    assert!(stderr(&output).contains("type can bitrate 250000`"));
    let output = run(&["read", swd, "node_id", "--can", "socketcan:vcan9"]);
    assert!(
        stderr(&output).contains("`ip link add dev vcan9 type vcan && ip link set vcan9 up`"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn bad_forms_and_bitrates_are_usage_errors() {
    let swd = swd();
    let swd = swd.to_str().unwrap();
    let output = run(&["read", swd, "node_id", "--can", "pcan:usb1"]);
    assert!(
        stderr(&output).contains(
            "--can pcan:usb1: expected socketcan:IFACE, slcan:/dev/PATH, slcan:HOST:PORT or candump:exec:COMMAND"
        ),
        "{}",
        stderr(&output)
    );
    let output = run(&["sim", swd, "--can", "candump:exec:cat"]);
    assert!(stderr(&output).contains("expected socketcan:IFACE"));
    let output = run(&["read", swd, "node_id", "--can", "candump:stdio"]);
    assert!(stderr(&output).contains("is for `drivegen sim`"));
    let output = run(&[
        "read",
        swd,
        "node_id",
        "--can",
        "slcan:/dev/x",
        "--bitrate",
        "333k",
    ]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("expected one of 10k, 20k, 50k, 100k, 125k, 250k, 500k, 800k, 1M"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn a_missing_serial_adapter_and_a_silent_one_are_named() {
    let swd = swd();
    let swd = swd.to_str().unwrap();
    let output = run(&[
        "read",
        swd,
        "node_id",
        "--can",
        "slcan:/dev/no-such-adapter",
    ]);
    assert_eq!(
        stderr(&output).trim(),
        "error: cannot open slcan:/dev/no-such-adapter: no such device /dev/no-such-adapter; is the adapter plugged in?"
    );
    // A pty nobody answers: the adapter's bit rate command (S8: the SWD's 1 Mbit/s) goes
    // unanswered.
    let pty = pty_pair();
    let spec = format!("slcan:{}", pty.client.display());
    let started = std::time::Instant::now();
    let output = run(&["read", swd, "node_id", "--can", &spec]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("the SLCAN adapter did not answer its `S8` command"),
        "{}",
        stderr(&output)
    );
    assert!(started.elapsed() < std::time::Duration::from_secs(5));
}

//! The CLI works in the configuration the drive reports (`[[variant]] selected_by`), as the
//! generated crate does: against pymodbus playing a Lenze smd (drives/lenze-smd/tests/peers/
//! smd_server.py) on a socat pty, c25 (`serial_baud_rate`) is #95 in PC400 and #103 in PC507,
//! where #95 is part of C99 (manual 004_e90b7fce7c8d5710.txt lines 348, 926, 944). A
//! configuration no variant covers reaches no moved register and writes nothing but a stop.

use std::process::{Command, Output};

use peer_support::{pty_pair, ready_peer, workspace_root, Process, PtyPair};

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

/// pymodbus serving `configuration` as #50, and the pty the CLI reaches it on.
struct Smd {
    _server: Process,
    pty: PtyPair,
}

fn smd(configuration: u16) -> Smd {
    let pty = pty_pair();
    let script = workspace_root().join("drives/lenze-smd/tests/peers/smd_server.py");
    let server = ready_peer(
        &script,
        &[pty.server.to_str().unwrap(), &configuration.to_string()],
    );
    Smd {
        _server: server,
        pty,
    }
}

impl Smd {
    /// `drivegen COMMAND descriptions/lenze-smd ARGS... --serial PTY ...` (9600 8N2, unit 10).
    fn drivegen(&self, command: &str, args: &[&str]) -> Output {
        let description = workspace_root().join("descriptions/lenze-smd");
        let serial = ["--serial", self.pty.client.to_str().unwrap()];
        let line = ["--baud", "9600", "--parity", "none", "--stop-bits", "2"];
        Command::new(BIN)
            .arg(command)
            .arg(description)
            .args(args)
            .args(serial)
            .args(line)
            .args(["--unit", "10", "--json"])
            .output()
            .unwrap()
    }

    /// The raw value `drivegen read` prints for `parameter`.
    fn read_raw(&self, parameter: &str, extra: &[&str]) -> serde_json::Value {
        let args: Vec<&str> = [parameter].iter().chain(extra).copied().collect();
        let out = self.drivegen("read", &args);
        assert!(out.status.success(), "{}", stderr(&out));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        json[0]["raw"].clone()
    }

    /// Unlocks parameter writes (#49 = C94, the peer's password 0).
    fn unlock_parameters(&self) {
        let out = self.drivegen("write", &["unlock_parameters", "raw:0"]);
        assert!(out.status.success(), "{}", stderr(&out));
    }
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn pc507_reads_and_writes_c25_at_103_and_leaves_95_alone() {
    let smd = smd(507);
    // #95 holds "SM" of C99's "SMD 2.01" in PC507; c25 at #103 holds 0.
    assert_eq!(smd.read_raw("serial_baud_rate", &[]), 0);
    smd.unlock_parameters();
    let out = smd.drivegen("write", &["serial_baud_rate", "raw:1"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(smd.read_raw("serial_baud_rate", &[]), 1);
    let c99 = serde_json::json!(b"SMD 2.01".to_vec());
    assert_eq!(smd.read_raw("software_version", &[]), c99, "#95 untouched");
}

#[test]
fn pc400_reads_and_writes_c25_at_95_and_leaves_103_alone() {
    let smd = smd(400);
    smd.unlock_parameters();
    let out = smd.drivegen("write", &["serial_baud_rate", "raw:2"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(smd.read_raw("serial_baud_rate", &[]), 2);
    // #103 is c70 in PC400: still the peer's 0.
    assert_eq!(smd.read_raw("trip_reset_configuration", &[]), 0);
    // Read as PC507 on purpose (--variant), #103 is that configuration's c25: untouched too.
    assert_eq!(smd.read_raw("serial_baud_rate", &["--variant", "pc507"]), 0);
}

#[test]
fn an_unknown_configuration_reaches_no_moved_register_and_writes_only_a_stop() {
    let smd = smd(401);
    let out = smd.drivegen("read", &["serial_baud_rate"]);
    assert!(!out.status.success());
    let why = stderr(&out);
    assert!(why.contains("parameter_configuration = 401"), "{why}");
    // A register at one address in every configuration still reads.
    assert_eq!(smd.read_raw("drive_family", &[]), 69);
    let out = smd.drivegen(
        "write",
        &["serial_speed_command", "raw:100", "--no-identity-check"],
    );
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("nothing was sent"),
        "{}",
        stderr(&out)
    );
    // The stop goes out although the identity (401) is not covered and the variant unknown:
    // the locked peer's own answer, exception 01, is what comes back.
    let out = smd.drivegen("write", &["stop", "raw:4"]);
    assert!(!out.status.success());
    let why = stderr(&out);
    assert!(
        why.contains("stop") && why.to_lowercase().contains("illegal function"),
        "{why}"
    );
}

#[test]
fn an_unknown_variant_name_is_a_usage_error() {
    let smd = smd(507);
    let out = smd.drivegen("read", &["serial_baud_rate", "--variant", "pc999"]);
    assert!(!out.status.success());
    assert!(stderr(&out).contains("pc400, pc507"), "{}", stderr(&out));
}

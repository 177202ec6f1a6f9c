//! The `drivegen` binary end to end against the simulator: help, read/write/watch by name with
//! units, refusals before anything is sent, a dead bus, `sim` and `decode`.

use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use drivebus::modbus::UnitId;
use drivesim::modbus::tcp::TcpServer;
use drivesim::Simulator;

mod support;

use support::{drivegen, stderr, stdout, BIN};

fn lafert_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/lafert-smartris")
}

fn simulated_lafert() -> (Simulator, TcpServer, String) {
    let sim = Simulator::load(lafert_path()).unwrap();
    sim.preset("operation_mode", 2).unwrap();
    sim.preset("bus_dc_link", 4950).unwrap();
    // An L motor (line 783): the speed setpoint lies within ±3000 rpm.
    sim.preset("full_scale_velocity", 3000).unwrap();
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let addr = server.local_addr().to_string();
    (sim, server, addr)
}

fn raw(sim: &Simulator, name: &str) -> i128 {
    sim.with(|drive| {
        let store = drive.store();
        store.int(store.id(name).unwrap()).unwrap()
    })
}

#[test]
fn every_subcommand_has_help() {
    for command in [
        "check", "dump", "generate", "sim", "read", "write", "watch", "decode", "network",
    ] {
        let output = drivegen(&[command, "--help"]);
        assert!(output.status.success(), "{command} --help");
        assert!(
            stdout(&output).contains("Usage: drivegen"),
            "{command}: {}",
            stdout(&output)
        );
    }
}

#[test]
fn read_prints_values_with_units_and_names() {
    let (_sim, _server, addr) = simulated_lafert();
    let lafert = lafert_path();
    let output = drivegen(&[
        "read",
        lafert.to_str().unwrap(),
        "bus_dc_link",
        "drive_status",
        "operation_mode",
        "--modbus-tcp",
        &addr,
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains("bus_dc_link     49.50 V   4950"), "{text}");
    assert!(text.contains("drive_status    standby   2"), "{text}");
    assert!(text.contains("operation_mode  velocity  2"), "{text}");
}

/// Both tables in one batch, sent together; out-of-range windows are usage errors.
#[test]
fn reads_may_keep_several_requests_in_flight() {
    let (_sim, _server, addr) = simulated_lafert();
    let lafert = lafert_path();
    let read = |in_flight: &str| {
        drivegen(&[
            "read",
            lafert.to_str().unwrap(),
            "bus_dc_link",
            "operation_mode",
            "velocity_average",
            "--modbus-tcp",
            &addr,
            "--max-in-flight",
            in_flight,
        ])
    };
    let (one, eight) = (read("1"), read("8"));
    assert!(eight.status.success(), "{}", stderr(&eight));
    assert!(
        stdout(&eight).contains("operation_mode    velocity  2"),
        "{}",
        stdout(&eight)
    );
    assert_eq!(stdout(&one), stdout(&eight));
    for refused in ["0", "17"] {
        let output = read(refused);
        assert_eq!(output.status.code(), Some(2), "clap usage error");
        assert!(
            stderr(&output).contains("--max-in-flight"),
            "{}",
            stderr(&output)
        );
    }
}

#[test]
fn read_json_is_machine_readable() {
    let (_sim, _server, addr) = simulated_lafert();
    let lafert = lafert_path();
    let output = drivegen(&[
        "read",
        lafert.to_str().unwrap(),
        "bus_dc_link",
        "--modbus-tcp",
        &addr,
        "--json",
    ]);
    let json: serde_json::Value = serde_json::from_str(&stdout(&output)).unwrap();
    assert_eq!(json[0]["parameter"], "bus_dc_link");
    assert_eq!(json[0]["value"], 49.5);
    assert_eq!(json[0]["raw"], 4950);
    assert_eq!(json[0]["unit"], "V");
}

#[test]
fn write_takes_engineering_units_and_names() {
    let (sim, _server, addr) = simulated_lafert();
    let lafert = lafert_path();
    let lafert = lafert.to_str().unwrap();
    let run = drivegen(&[
        "write",
        lafert,
        "control_word",
        "run|stop_disabled",
        "--modbus-tcp",
        &addr,
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert_eq!(raw(&sim, "drive_status"), 0x0001, "RUN after T2");
    let speed = drivegen(&[
        "write",
        lafert,
        "speed_setpoint",
        "-1500rpm",
        "--modbus-tcp",
        &addr,
    ]);
    assert!(speed.status.success(), "{}", stderr(&speed));
    assert_eq!(raw(&sim, "speed_setpoint"), -1500);
    let beyond = drivegen(&[
        "write",
        lafert,
        "speed_setpoint",
        "-3001rpm",
        "--modbus-tcp",
        &addr,
    ]);
    assert!(!beyond.status.success());
    assert!(
        stderr(&beyond).contains("beyond the current value 3000 of full_scale_velocity"),
        "{}",
        stderr(&beyond)
    );
    assert_eq!(raw(&sim, "speed_setpoint"), -1500, "nothing written");
}

#[test]
fn bad_values_are_refused_before_anything_is_sent() {
    let (sim, _server, addr) = simulated_lafert();
    let lafert = lafert_path();
    let lafert = lafert.to_str().unwrap();
    let cases = [
        (
            "speed_ramp_up",
            "2V",
            "wrong unit `V`: the parameter is in ms",
        ),
        (
            "speed_ramp_up",
            "40000ms",
            "outside the range of speed_ramp_up: 0 ms..=32000 ms",
        ),
        (
            "ramp_enable",
            "2",
            "not allowed for ramp_enable; allowed: 0, 1",
        ),
    ];
    for (parameter, value, message) in cases {
        let output = drivegen(&["write", lafert, parameter, value, "--modbus-tcp", &addr]);
        assert!(!output.status.success());
        assert!(
            stderr(&output).contains(message),
            "{parameter} {value}: {}",
            stderr(&output)
        );
        assert!(stderr(&output).contains("nothing was sent"));
    }
    assert_eq!(raw(&sim, "speed_ramp_up"), 2000, "unchanged");
    assert_eq!(raw(&sim, "ramp_enable"), 1, "unchanged");
}

#[test]
fn unknown_names_suggest_the_closest() {
    let lafert = lafert_path();
    let output = drivegen(&[
        "read",
        lafert.to_str().unwrap(),
        "bus_dc_lnk",
        "--modbus-tcp",
        "127.0.0.1:1",
    ]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("did you mean `bus_dc_link`"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn a_dead_bus_times_out_naming_the_address() {
    // Accepts the connection and never answers.
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap().to_string();
    let lafert = lafert_path();
    let started = Instant::now();
    let output = drivegen(&[
        "read",
        lafert.to_str().unwrap(),
        "bus_dc_link",
        "--modbus-tcp",
        &addr,
        "--timeout-ms",
        "200",
    ]);
    assert!(!output.status.success());
    let expected = format!("bus_dc_link: no answer from Modbus TCP {addr} unit 1 (timeout)");
    assert!(stderr(&output).contains(&expected), "{}", stderr(&output));
    assert!(started.elapsed() < Duration::from_secs(10), "no hang");
    drop(listener);
}

#[test]
fn watch_polls_until_the_count() {
    let (_sim, _server, addr) = simulated_lafert();
    let lafert = lafert_path();
    let output = drivegen(&[
        "watch",
        lafert.to_str().unwrap(),
        "drive_status",
        "bus_dc_link",
        "--modbus-tcp",
        &addr,
        "--count",
        "3",
        "--interval-ms",
        "10",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    let polls = text
        .lines()
        .filter(|l| l.contains("standby") && l.contains("49.50 V"))
        .count();
    assert_eq!(polls, 3, "{text}");
}

#[test]
fn sim_announces_its_real_port_and_serves_until_stopped() {
    let lafert = lafert_path();
    let (mut child, addr) = support::modbus_sim(&lafert, &["--set", "bus_dc_link=4950"]);
    assert!(!addr.ends_with(":0"), "the real port: {addr}");
    let output = drivegen(&[
        "read",
        lafert.to_str().unwrap(),
        "bus_dc_link",
        "--modbus-tcp",
        &addr,
    ]);
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(stdout(&output).contains("49.50 V"), "{}", stderr(&output));
}

#[test]
fn decode_names_sdo_values_heartbeats_and_emcy() {
    let dir = std::env::temp_dir().join(format!("drivegen-decode-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let log = dir.join("capture.log");
    std::fs::write(
        &log,
        "(1700000000.000100) can0 701#00\n\
         (1700000000.000200) can0 601#2B40600006000000\n\
         (1700000000.000300) can0 581#6040600000000000\n\
         (1700000000.000400) can0 601#4041600000000000\n\
         (1700000000.000500) can0 581#4B41600021020000\n\
         (1700000000.000600) can0 081#1032010000000000\n\
         (1700000000.000700) can0 581#8041600002000106\n\
         (1700000000.000800) can0 601#23001A0110004160\n\
         (1700000000.000900) can0 601#2F001A0001000000\n\
         (1700000000.001000) can0 181#2702\n",
    )
    .unwrap();
    let lafert = lafert_path();
    let output = drivegen(&["decode", lafert.to_str().unwrap(), log.to_str().unwrap()]);
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(
        text.contains("heartbeat") && text.contains("Initializing"),
        "{text}"
    );
    assert!(text.contains("write controlword"), "{text}");
    assert!(text.contains("statusword"), "{text}");
    assert!(
        text.contains("over_voltage"),
        "EMCY 0x3210 named from the error code enum: {text}"
    );
    assert!(
        text.contains("0x06010002 attempt to write a read only object"),
        "{text}"
    );
}

#[test]
fn sim_is_a_canopen_node_on_slcan_over_tcp() {
    use drivebus::canopen::can::slcan::SlcanBus;
    use drivebus::canopen::client::BlockingSdo;
    use drivebus::canopen::{NodeId, SdoBus};

    // The simulator connects to an SLCAN gateway; the test is the gateway and the master.
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap();
    let lafert = lafert_path();
    let mut child = Command::new(BIN)
        .args([
            "sim",
            lafert.to_str().unwrap(),
            "--can",
            &format!("slcan:{addr}"),
        ])
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    let (stream, _) = listener.accept().unwrap();
    let mut sdo =
        BlockingSdo::new(SlcanBus::tcp(stream).unwrap()).with_timeout(Duration::from_secs(2));
    let mut buf = [0u8; 2];
    let result = sdo.upload(NodeId(1), 0x6041, 0, &mut buf);
    child.kill().unwrap();
    child.wait().unwrap();
    assert_eq!(result, Ok(2));
    assert_eq!(u16::from_le_bytes(buf) & 0x4F, 0x40, "switch on disabled");
}

#[test]
fn two_word_values_are_written_word_by_word_without_fc16() {
    // The Lafert implements FC 0x06 only (functions = [0x03, 0x04, 0x06]).
    let (sim, _server, addr) = simulated_lafert();
    let lafert = lafert_path();
    let output = drivegen(&[
        "write",
        lafert.to_str().unwrap(),
        "s_ramp_jerk_acceleration",
        "raw:1000000",
        "--modbus-tcp",
        &addr,
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(raw(&sim, "s_ramp_jerk_acceleration"), 1_000_000);
}

#[test]
fn diff_classifies_changes_and_fails_only_on_breaking_ones() {
    let lafert = lafert_path();
    let lafert = lafert.to_str().unwrap();
    let same = drivegen(&["diff", lafert, lafert]);
    assert!(same.status.success(), "{}", stderr(&same));
    assert_eq!(stdout(&same), "no changes\n");

    let original = std::fs::read_to_string(lafert_path().join("device.toml")).unwrap();
    let profiles = lafert_path().join("../profiles/");
    let changed = original
        .replace("\"../profiles/", &format!("\"{}/", profiles.display()))
        .replace(
            "unit = \"V\"\nscale = \"1/100\"\nmodbus = { table = \"input\", address = 0x0064",
            "unit = \"mV\"\nscale = \"10\"\nmodbus = { table = \"input\", address = 0x0064",
        );
    assert_ne!(changed, original, "the edit applies to bus_dc_link");
    let dir = std::env::temp_dir().join(format!("drivegen-diff-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("device.toml"), changed).unwrap();
    let output = drivegen(&["diff", lafert, dir.to_str().unwrap()]);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert_eq!(
        stdout(&output),
        "breaking (1):\n  parameter `bus_dc_link`: value type `Volts` → `Millivolts`\n\
         behaviour (1):\n  parameter `bus_dc_link`: scale 1/100 → 10\n\
         2 change(s), 1 breaking\n"
    );
    assert!(
        stderr(&output).contains("1 breaking change(s)"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn write_checks_the_identity_first_unless_told_not_to() {
    let (sim, _server, addr) = simulated_lafert();
    sim.preset("fw_release", 226).unwrap();
    let lafert = lafert_path();
    let lafert = lafert.to_str().unwrap();
    let write = |extra: &[&str]| {
        let mut args = vec![
            "write",
            lafert,
            "speed_setpoint",
            "-1500rpm",
            "--modbus-tcp",
            &addr,
        ];
        args.extend_from_slice(extra);
        drivegen(&args)
    };
    let refused = write(&[]);
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("fw_release reads 226, the description covers [242]"),
        "{}",
        stderr(&refused)
    );
    assert_eq!(raw(&sim, "speed_setpoint"), 0, "nothing written");
    let forced = write(&["--no-identity-check"]);
    assert!(forced.status.success(), "{}", stderr(&forced));
    assert_eq!(raw(&sim, "speed_setpoint"), -1500);
}

#[test]
fn write_checks_the_canopen_vendor_id_first() {
    // The SWD's [identity] covers vendor-ID 0x515 (1018h sub 1, manual line 1129); this
    // simulated node reports 0x1234.
    let (swd, can) = foreign_swd();
    let write = |extra: &[&str]| {
        let mut args = vec![
            "write",
            &swd,
            "controlword",
            "raw:15",
            "--can",
            &can,
            "--node-id",
            "4",
            "--timeout-ms",
            SIM_STARTUP_MS,
        ];
        args.extend_from_slice(extra);
        drivegen(&args)
    };
    let refused = write(&[]);
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("vendor_id reads 4660, the description covers [1301]"),
        "{}",
        stderr(&refused)
    );
    let forced = write(&["--no-identity-check"]);
    assert!(forced.status.success(), "{}", stderr(&forced));
}

#[test]
fn write_sends_a_stop_whatever_the_identity_reads() {
    // Shutdown (6040h = 6: enable operation clear) stops the drive: it goes out although the
    // simulated node's vendor-ID (0x1234) is not the one the SWD's [identity] covers.
    let (swd, can) = foreign_swd();
    let stop = drivegen(&[
        "write",
        &swd,
        "controlword",
        "raw:6",
        "--can",
        &can,
        "--node-id",
        "4",
        "--timeout-ms",
        SIM_STARTUP_MS,
    ]);
    assert!(stop.status.success(), "{}", stderr(&stop));
}

/// The answer timeout of a request to a simulator the command spawns (`candump:exec:`): the first
/// request goes out while the child still loads its description (0.3 s on an idle machine, over
/// the default 1 s on a loaded CI machine) and waits in its pipe until then.
const SIM_STARTUP_MS: &str = "10000";

/// The SWD description and a `--can` backend: its simulated node 4, reporting vendor-ID 0x1234.
fn foreign_swd() -> (String, String) {
    let swd = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/ezwheel-swd");
    let swd = swd.to_str().unwrap().to_owned();
    let can = format!(
        "candump:exec:{BIN} sim {swd} --can candump:stdio --node-id 4 --set vendor_id=0x1234"
    );
    (swd, can)
}

/// Issue #27 item 7: a vendor EDS whose `$NODEID+0x180` COB-ID default has limits 0x181..=0x18F
/// (node IDs 1..=15; its `gateway_id`, node IDs 16..=32). At node 5 the session says nothing of
/// the COB-ID and the simulated node holds 0x185; at node 16 the session and the simulated node
/// (its stderr is inherited) each warn, naming the parameter, its default there and the node IDs
/// allowed, and the read still gives 0x190 (what the drive holds); a write of that default is
/// refused before the bus is even opened, one within the limits goes through.
#[test]
fn a_node_id_the_limits_do_not_allow_is_warned_about_and_not_refused() {
    let eds = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../codegen/tests/eds/node_id_default_narrowed.eds");
    let eds = eds.to_str().unwrap();
    let run = |node: &str, command: &[&str]| {
        let can = format!("candump:exec:{BIN} sim {eds} --can candump:stdio --node-id {node}");
        let mut args = command.to_vec();
        args.extend_from_slice(&["--can", &can, "--node-id", node]);
        args.extend_from_slice(&["--timeout-ms", SIM_STARTUP_MS]);
        drivegen(&args)
    };
    let read = ["read", eds, "cob_id_used_by_tpdo1", "--json"];
    let warning = |node: u8, name: &str, value: u32, allowed: &str| {
        format!("warning: on node {node} the default of `{name}`, {value}, is outside what the description allows for it; it allows node IDs {allowed} only\n")
    };

    let allowed = run("5", &read);
    let text = stderr(&allowed);
    assert!(allowed.status.success(), "{text}");
    assert!(
        !text.contains("default of `cob_id_used_by_tpdo1`, "),
        "{text}"
    );
    let gateway = warning(5, "gateway_id", 261, "16..=32");
    assert_eq!(text.matches(&gateway).count(), 2, "read and sim: {text}");
    assert!(
        stdout(&allowed).contains("389"),
        "0x185: {}",
        stdout(&allowed)
    );

    let cob_id = warning(16, "cob_id_used_by_tpdo1", 400, "1..=15");
    let outside = run("16", &read);
    let text = stderr(&outside);
    assert!(outside.status.success(), "{text}");
    assert_eq!(text.matches(&cob_id).count(), 2, "read and sim: {text}");
    assert!(!text.contains("default of `gateway_id`, "), "{text}");
    assert!(
        stdout(&outside).contains("400"),
        "0x190: {}",
        stdout(&outside)
    );

    let refused = run("16", &["write", eds, "cob_id_used_by_tpdo1", "raw:400"]);
    assert!(!refused.status.success(), "{}", stdout(&refused));
    let why = stderr(&refused);
    assert!(
        why.contains("400 is outside the range of cob_id_used_by_tpdo1: 385..=399")
            && why.contains("(nothing was sent)"),
        "{why}"
    );
    let within = run("16", &["write", eds, "cob_id_used_by_tpdo1", "raw:385"]);
    assert!(within.status.success(), "{}", stderr(&within));
}

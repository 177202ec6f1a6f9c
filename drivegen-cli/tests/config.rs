//! `drivegen config pull / push / compare` end to end against the simulator, one test per
//! family over its protocol: Lafert and Lenze over Modbus TCP, the Kinco FD over Modbus TCP and
//! RS-232 (a socat pty pair to `drivegen sim`), the ez-Wheel SWD over CANopen (candump lines over
//! TCP through socat). Each pulls, changes values on the simulated drive, compares (different),
//! pushes, and compares again (equal), with the simulated drive holding the pulled values. The
//! Lenze smd is locked: the push unlocks it as its description says and locks it again. Bad
//! files are refused with the line, and nothing is written.

use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::thread;

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::NodeId;
use drivebus::modbus::UnitId;
use drivesim::canopen::{nodes, Node, NodeConfig};
use drivesim::modbus::tcp::TcpServer;
use drivesim::Simulator;

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn description(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../descriptions")
        .join(name)
}

fn drivegen(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

fn text(output: &Output) -> String {
    format!(
        "stdout:\n{}\nstderr:\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

fn raw(sim: &Simulator, name: &str) -> i128 {
    sim.with(|drive| {
        let store = drive.store();
        store.int(store.id(name).unwrap()).unwrap()
    })
}

/// A file in a fresh folder for this test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("drivegen-config-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join("drive.toml")
}

fn modbus(sim: &Simulator) -> (TcpServer, Vec<String>) {
    let server = sim.serve_modbus_tcp("127.0.0.1:0", UnitId(1)).unwrap();
    let addr = server.local_addr().to_string();
    (server, vec!["--modbus-tcp".into(), addr])
}

/// Serves `sim` as CANopen node `node` to one CLI run after another: candump lines over TCP,
/// reached through `socat` as a `candump:exec:` backend, so the simulated drive (and what is
/// written to it) outlives each run.
fn canopen(sim: &Simulator, node: u8) -> Vec<String> {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap();
    let sim = sim.clone();
    thread::spawn(move || {
        for stream in listener.incoming() {
            let Ok(stream) = stream else { return };
            let config = NodeConfig {
                node: NodeId(node),
                heartbeat: None,
            };
            let mut node = Node::new(sim.clone(), config, sim.variant());
            let mut bus = CandumpBus::new(stream.try_clone().unwrap(), stream);
            // The run ends when the CLI closes the connection.
            let _ = nodes::run(std::slice::from_mut(&mut node), &mut bus);
        }
    });
    vec![
        "--can".into(),
        format!("candump:exec:socat - TCP:{addr}"),
        "--node-id".into(),
        node.to_string(),
    ]
}

/// The line of the push report that says `name` was written.
fn written_at(report: &str, name: &str) -> usize {
    report
        .lines()
        .position(|l| {
            l.starts_with(&format!("{name} "))
                && (l.ends_with("  written") || l.contains("  written (takes effect"))
        })
        .unwrap_or_else(|| panic!("{name} not written: {report}"))
}

fn run(command: &[&str], bus: &[String]) -> Output {
    let mut args: Vec<&str> = command.to_vec();
    args.extend(bus.iter().map(String::as_str));
    drivegen(&args)
}

/// `config pull` of `description` into `file`, which must succeed.
fn pull(description: &Path, file: &Path, bus: &[String]) {
    let (description, file) = (description.to_str().unwrap(), file.to_str().unwrap());
    let pull = run(&["config", "pull", description, "-o", file], bus);
    assert!(pull.status.success(), "{}", text(&pull));
}

/// Pull, change `changes` on the drive, compare, dry run, push, compare: the drive ends as
/// pulled. Returns the push's output.
fn round_trip(
    test: &str,
    sim: &Simulator,
    description: &Path,
    bus: &[String],
    changes: &[(&str, i128)],
) -> Output {
    let file = scratch(test);
    let file_s = file.to_str().unwrap();
    pull(description, &file, bus);
    let pulled: Vec<i128> = changes.iter().map(|(name, _)| raw(sim, name)).collect();
    for ((name, value), was) in changes.iter().zip(&pulled) {
        assert_ne!(value, was, "{name}: the change changes it");
        sim.preset(name, *value).unwrap();
    }
    let differs = run(&["config", "compare", file_s], bus);
    assert_eq!(differs.status.code(), Some(1), "{}", text(&differs));
    for (name, _) in changes {
        assert!(text(&differs).contains(name), "{name}: {}", text(&differs));
    }
    let dry = run(&["config", "push", file_s, "--dry-run"], bus);
    assert!(dry.status.success(), "{}", text(&dry));
    for (name, value) in changes {
        assert!(text(&dry).contains(name), "{name}: {}", text(&dry));
        assert_eq!(raw(sim, name), *value, "{name}: a dry run writes nothing");
    }
    let push = run(&["config", "push", file_s], bus);
    assert!(push.status.success(), "{}", text(&push));
    for ((name, _), was) in changes.iter().zip(&pulled) {
        assert_eq!(raw(sim, name), *was, "{name} written back");
        assert!(
            text(&push).contains(&format!("{name}  ")),
            "{name}: {}",
            text(&push)
        );
    }
    let equal = run(&["config", "compare", file_s], bus);
    assert_eq!(equal.status.code(), Some(0), "{}", text(&equal));
    assert!(text(&equal).contains("no differences"), "{}", text(&equal));
    push
}

#[test]
fn lafert_round_trip_over_modbus() {
    let lafert = description("lafert-smartris");
    let sim = Simulator::load(&lafert).unwrap();
    sim.preset("operation_mode", 2).unwrap();
    let (_server, bus) = modbus(&sim);
    let push = round_trip(
        "lafert",
        &sim,
        &lafert,
        &bus,
        &[
            ("speed_ramp_up", 1500),
            ("limit_torque_positive", 50),
            ("operation_mode", 1),
            ("communication_loss_time", 500),
        ],
    );
    let out = text(&push);
    // The mode goes first, whatever the description's order.
    assert!(
        written_at(&out, "operation_mode") < written_at(&out, "speed_ramp_up"),
        "{out}"
    );
    assert!(out.contains("4 written, 53 unchanged, 0 refused"), "{out}");
    assert!(
        out.contains("written (takes effect after the store and a reset)"),
        "{out}"
    );
    assert!(out.contains("store (store_eeprom)"), "{out}");
}

#[test]
fn kinco_round_trip_over_modbus() {
    let kinco = description("kinco-fd");
    let sim = Simulator::load(&kinco).unwrap();
    // Gains within their ranges, as a commissioned drive holds them.
    sim.preset("kvp", 100).unwrap();
    sim.preset("kpp", 200).unwrap();
    let (_server, bus) = modbus(&sim);
    round_trip(
        "kinco",
        &sim,
        &kinco,
        &bus,
        &[("kvp", 123), ("kpp", 456), ("din_position3", -20_000)],
    );
}

#[test]
fn swd_round_trip_over_canopen() {
    let swd = description("ezwheel-swd");
    let sim = Simulator::load(&swd).unwrap();
    let bus = canopen(&sim, 16);
    let push = round_trip(
        "swd",
        &sim,
        &swd,
        &bus,
        &[
            ("rpdo1_event_timer", 250),
            ("rpdo1_transmission_type", 254),
            ("tpdo1_mapping_entry_2", 0x6041_0010),
        ],
    );
    // The mapping changes in the CiA 301 sequence: PDO invalid, mapping disabled, the entry,
    // mapping enabled, PDO valid.
    let out = text(&push);
    let written: Vec<&str> = out
        .lines()
        .filter(|l| l.starts_with("tpdo1_") && l.contains("  written"))
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    assert_eq!(
        written,
        [
            "tpdo1_cob_id",
            "tpdo1_mapping_count",
            "tpdo1_mapping_entry_2",
            "tpdo1_mapping_count",
            "tpdo1_cob_id"
        ],
        "{out}"
    );
}

#[test]
fn a_locked_lenze_is_unlocked_as_described_and_locked_again() {
    let lenze = description("lenze-smd");
    let sim = Simulator::load(&lenze).unwrap();
    let (_server, bus) = modbus(&sim);
    let locked = |sim: &Simulator| {
        let write = run(
            &[
                "write",
                lenze.to_str().unwrap(),
                "acceleration_time",
                "raw:70",
                "--no-identity-check",
            ],
            &bus,
        );
        let refused = !write.status.success();
        assert!(
            refused || raw(sim, "acceleration_time") == 70,
            "{}",
            text(&write)
        );
        refused
    };
    assert!(locked(&sim), "the simulated smd powers up locked");
    let push = round_trip(
        "lenze",
        &sim,
        &lenze,
        &bus,
        &[("acceleration_time", 120), ("current_limit", 90)],
    );
    let out = text(&push);
    let unlock = written_at(&out, "unlock parameter_writing (unlock_parameters)");
    let relock = written_at(&out, "lock (lock_security)");
    for name in ["acceleration_time", "current_limit"] {
        assert!((unlock..relock).contains(&written_at(&out, name)), "{out}");
    }
    assert!(locked(&sim), "locked again after the push");
}

/// A Lafert file pulled from a simulated drive, the drive (its speed ramp changed since), and
/// the bus.
fn pulled_lafert(test: &str) -> (PathBuf, Simulator, TcpServer, Vec<String>) {
    let lafert = description("lafert-smartris");
    let sim = Simulator::load(&lafert).unwrap();
    sim.preset("operation_mode", 2).unwrap();
    let (server, bus) = modbus(&sim);
    let file = scratch(test);
    pull(&lafert, &file, &bus);
    sim.preset("speed_ramp_up", 1500).unwrap();
    (file, sim, server, bus)
}

/// `file` with `from` replaced by `to` (which must change it), as a new file.
fn edited(file: &Path, from: &str, to: &str) -> (PathBuf, String) {
    let original = std::fs::read_to_string(file).unwrap();
    let changed = original.replacen(from, to, 1);
    assert_ne!(changed, original, "{from} is in the file");
    let path = file.with_file_name(format!("edited-{}.toml", to.len()));
    std::fs::write(&path, &changed).unwrap();
    (path, changed)
}

/// The 1-based line of `text` that starts with `start`.
fn line_of(text: &str, start: &str) -> usize {
    text.lines().position(|l| l.starts_with(start)).unwrap() + 1
}

/// Pushes `file`: refused (exit code 2) with `expected` in the error, and nothing written.
fn refused(file: &Path, sim: &Simulator, bus: &[String], expected: &str) {
    let push = run(&["config", "push", file.to_str().unwrap()], bus);
    assert_eq!(push.status.code(), Some(2), "{}", text(&push));
    assert!(
        text(&push).contains(expected),
        "{expected}: {}",
        text(&push)
    );
    assert_eq!(raw(sim, "speed_ramp_up"), 1500, "nothing written");
}

#[test]
fn an_edited_value_out_of_range_is_refused_with_its_line() {
    let (file, sim, _server, bus) = pulled_lafert("range");
    let (edited, changed) = edited(
        &file,
        "speed_ramp_up = { value = \"2000 ms\"",
        "speed_ramp_up = { value = \"70000 ms\"",
    );
    let line = line_of(&changed, "speed_ramp_up");
    refused(
        &edited,
        &sim,
        &bus,
        &format!(
            "{}:{line}: speed_ramp_up: 70000 ms does not fit u16",
            edited.display()
        ),
    );
    // An edit within the range is written, as edited.
    let (within, _) = edited_within(&file);
    let push = run(&["config", "push", within.to_str().unwrap()], &bus);
    assert!(push.status.success(), "{}", text(&push));
    assert_eq!(raw(&sim, "speed_ramp_up"), 2500);
}

fn edited_within(file: &Path) -> (PathBuf, String) {
    edited(
        file,
        "speed_ramp_up = { value = \"2000 ms\"",
        "speed_ramp_up = { value = \"2500ms\"",
    )
}

#[test]
fn a_parameter_the_description_does_not_have_is_refused_with_its_line() {
    let (file, sim, _server, bus) = pulled_lafert("unknown");
    let (edited, changed) = edited(&file, "\nspeed_ramp_up = ", "\nspeed_ramp_upp = ");
    let line = line_of(&changed, "speed_ramp_upp");
    refused(
        &edited,
        &sim,
        &bus,
        &format!(
            "{}:{line}: `speed_ramp_upp` is not a parameter of Lafert Smartris; did you mean `speed_ramp_up`?",
            edited.display()
        ),
    );
}

#[test]
fn a_truncated_file_is_refused_with_its_line() {
    let (file, sim, _server, bus) = pulled_lafert("truncated");
    let whole = std::fs::read_to_string(&file).unwrap();
    let cut = &whole[..whole.find("speed_ramp_down = {").unwrap() + 30];
    let truncated = file.with_file_name("truncated.toml");
    std::fs::write(&truncated, cut).unwrap();
    let line = line_of(cut, "speed_ramp_down");
    refused(
        &truncated,
        &sim,
        &bus,
        &format!("{}:{line}: not a configuration file", truncated.display()),
    );
}

#[test]
fn a_file_of_another_drive_or_firmware_is_refused() {
    let (file, sim, _server, bus) = pulled_lafert("foreign");
    // Another description: the file names the Lafert.
    let lenze = description("lenze-smd");
    let push = run(
        &[
            "config",
            "push",
            file.to_str().unwrap(),
            "--description",
            lenze.to_str().unwrap(),
        ],
        &bus,
    );
    assert_eq!(push.status.code(), Some(2), "{}", text(&push));
    assert!(
        text(&push).contains(
            "the file was read from a Lafert Smartris drive, the description is of Lenze smd"
        ),
        "{}",
        text(&push)
    );
    // Another firmware on the drive: the description does not cover it, and the file was read
    // from 242.
    sim.preset("fw_release", 226).unwrap();
    refused(
        &file,
        &sim,
        &bus,
        "fw_release reads 226, the description covers [242]",
    );
    let forced = run(
        &[
            "config",
            "push",
            file.to_str().unwrap(),
            "--no-identity-check",
        ],
        &bus,
    );
    assert_eq!(forced.status.code(), Some(2), "{}", text(&forced));
    let whole = std::fs::read_to_string(&file).unwrap();
    let line = line_of(&whole, "fw_release");
    assert!(
        text(&forced).contains(&format!(
            "{}:{line}: fw_release was 242 when the file was read",
            file.display()
        )),
        "{}",
        text(&forced)
    );
    assert_eq!(raw(&sim, "speed_ramp_up"), 1500, "nothing written");
}

#[test]
fn two_files_compare_by_value() {
    let (file, _sim, _server, _bus) = pulled_lafert("files");
    let same = drivegen(&[
        "config",
        "compare",
        file.to_str().unwrap(),
        file.to_str().unwrap(),
    ]);
    assert_eq!(same.status.code(), Some(0), "{}", text(&same));
    let (within, _) = edited_within(&file);
    let differs = drivegen(&[
        "config",
        "diff",
        file.to_str().unwrap(),
        within.to_str().unwrap(),
    ]);
    assert_eq!(differs.status.code(), Some(1), "{}", text(&differs));
    assert!(
        text(&differs).contains("speed_ramp_up  2000 ms"),
        "{}",
        text(&differs)
    );
    assert!(text(&differs).contains("2500 ms"), "{}", text(&differs));
    // The simulated drive started from the description's defaults.
    let defaults =
        |file: &Path| drivegen(&["config", "compare", file.to_str().unwrap(), "--defaults"]);
    let as_shipped = defaults(&file);
    assert_eq!(as_shipped.status.code(), Some(0), "{}", text(&as_shipped));
    let edited = defaults(&within);
    assert_eq!(edited.status.code(), Some(1), "{}", text(&edited));
    let edited_text = text(&edited);
    let row = edited_text
        .lines()
        .find(|l| l.starts_with("speed_ramp_up"))
        .map(|l| {
            l.split("  ")
                .filter(|c| !c.is_empty())
                .map(str::trim)
                .collect::<Vec<_>>()
        });
    assert_eq!(
        row,
        Some(vec!["speed_ramp_up", "2500 ms", "2000 ms"]),
        "{}",
        text(&edited)
    );
}

/// A wrong password: the unlock does not take, every write is refused by the drive and reported
/// with its reason, the lock still goes out, and the push fails naming how many were not written.
#[test]
fn a_push_the_drive_refuses_is_reported_parameter_by_parameter() {
    let lenze = description("lenze-smd");
    let sim = Simulator::load(&lenze).unwrap();
    let (_server, bus) = modbus(&sim);
    let file = scratch("refused");
    let file_s = file.to_str().unwrap();
    pull(&lenze, &file, &bus);
    sim.preset("acceleration_time", 120).unwrap();
    sim.preset("current_limit", 90).unwrap();
    let push = run(&["config", "push", file_s, "--password", "5"], &bus);
    let out = text(&push);
    assert_eq!(push.status.code(), Some(2), "{out}");
    for name in ["acceleration_time", "current_limit"] {
        let line = out.lines().find(|l| l.starts_with(name)).unwrap();
        assert!(line.contains("refused: "), "{out}");
    }
    assert!(out.contains("lock (lock_security)"), "{out}");
    assert!(
        out.contains("2 of 2 parameter(s) not written as the file holds them"),
        "{out}"
    );
    assert_eq!(raw(&sim, "acceleration_time"), 120);
    assert_eq!(raw(&sim, "current_limit"), 90);
}

/// The Kinco FD over its RS-232 protocol, through a socat pty pair to `drivegen sim`: the values
/// are changed with `drivegen write` on the same line, and the push restores them.
#[test]
fn kinco_round_trip_over_rs232() {
    use peer_support::{pty_pair, Process};
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;

    let kinco = description("kinco-fd");
    let kinco_s = kinco.to_str().unwrap();
    let pty = pty_pair();
    let child = Command::new(BIN)
        .args(["sim", kinco_s, "--kinco-rs232"])
        .arg(&pty.server)
        .args(["--set", "kvp=100", "--set", "kpp=200"])
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut sim = Process::new(child);
    let mut line = String::new();
    BufReader::new(sim.child_mut().stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    assert!(line.starts_with("listening on kinco-rs232"), "{line}");
    let bus: Vec<String> = vec![
        "--kinco-rs232".into(),
        pty.client.display().to_string(),
        "--timeout-ms".into(),
        "300".into(),
    ];
    let file = scratch("kinco-rs232");
    let file_s = file.to_str().unwrap();
    pull(&kinco, &file, &bus);
    for (name, value) in [("kvp", "150"), ("din_position3", "-20000")] {
        let write = run(&["write", kinco_s, name, value], &bus);
        assert!(write.status.success(), "{}", text(&write));
    }
    let differs = run(&["config", "compare", file_s], &bus);
    assert_eq!(differs.status.code(), Some(1), "{}", text(&differs));
    let push = run(&["config", "push", file_s], &bus);
    assert!(push.status.success(), "{}", text(&push));
    for name in ["kvp", "din_position3"] {
        written_at(&text(&push), name);
    }
    let equal = run(&["config", "compare", file_s], &bus);
    assert_eq!(equal.status.code(), Some(0), "{}", text(&equal));
}

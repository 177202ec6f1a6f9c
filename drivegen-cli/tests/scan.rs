//! `drivegen scan` end to end against `drivegen sim` serving several drives at once: CANopen
//! nodes on one candump stream, Modbus units behind one TCP gateway and on one RTU line (a socat
//! pty). Each bus has a drive its description covers, a drive reporting a foreign identity (a
//! "no match" line, never a write) and silent ids that are not listed.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use drivebus::modbus::UnitId;
use drivesim::modbus::tcp::TcpServer;
use drivesim::modbus::Units;
use drivesim::Simulator;
use peer_support::{pty_pair, Process};

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn description(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../descriptions")
        .join(name)
}

fn path(name: &str) -> String {
    description(name).to_str().unwrap().to_owned()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn scan(args: &[&str]) -> Output {
    let output = Command::new(BIN).arg("scan").args(args).output().unwrap();
    assert!(output.status.success(), "{}", text(&output.stderr));
    output
}

/// The line of `id` (`node   5: ...` / `unit   3: ...`), if listed.
fn line_of<'a>(out: &'a str, kind: &str, id: u8) -> Option<&'a str> {
    let head = format!("{kind} {id:3}:");
    out.lines().find(|l| l.starts_with(&head))
}

/// A scratch folder for one test, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("drivegen-scan-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[test]
fn canopen_scan_names_each_node_and_its_description_and_writes_nothing() {
    // One simulator process is a whole bus: the SWD at node 5, an SWD reporting a foreign
    // vendor-ID at node 6, a Kinco (no [identity]) at node 9; every other id is silent. A
    // script in front of it records every frame the scan sends.
    let scratch = Scratch::new("canopen");
    let log = scratch.0.join("sent.log");
    let script = scratch.0.join("bus.sh");
    let (swd, kinco) = (path("ezwheel-swd"), path("kinco-fd"));
    std::fs::write(
        &script,
        format!(
            "#!/bin/sh\ntee {log} | {BIN} sim {swd} {swd} {kinco} --can candump:stdio \
             --node-id 5 --node-id 6 --node-id 9 --set 6:vendor_id=0x1234 2>/dev/null\n",
            log = log.display()
        ),
    )
    .unwrap();
    let can = format!("candump:exec:sh {}", script.display());
    // The timeout covers the simulator's start-up: the requests wait in its input meanwhile.
    let args = ["--can", can.as_str(), "--timeout-ms", "3000"];
    let out = text(
        &scan(&[&args[..], &["--description", &swd, "--description", &kinco]].concat()).stdout,
    );
    let listed: Vec<&str> = out.lines().collect();
    assert_eq!(
        listed.len(),
        3,
        "only the three simulated nodes answer:\n{out}"
    );
    let covered = line_of(&out, "node", 5).unwrap();
    assert!(covered.contains("vendor-ID 0x00000515"), "{covered}");
    assert!(covered.ends_with(": ez-Wheel SWD"), "{covered}");
    let foreign = line_of(&out, "node", 6).unwrap();
    assert!(foreign.contains("vendor-ID 0x00001234"), "{foreign}");
    assert!(foreign.ends_with(": no match"), "{foreign}");
    assert!(line_of(&out, "node", 9).unwrap().ends_with(": no match"));
    assert!(
        line_of(&out, "node", 7).is_none(),
        "a silent id is not listed"
    );
    let sent = std::fs::read_to_string(&log).unwrap();
    assert!(
        sent.lines().count() >= 127,
        "every node id was asked:\n{sent}"
    );
    for frame in sent.lines() {
        let (id, data) = frame.split_once('#').unwrap();
        let id = u16::from_str_radix(id, 16).unwrap();
        assert!((0x601..=0x67F).contains(&id), "only SDO requests: {frame}");
        assert_eq!(
            &data[..1],
            "4",
            "only expedited uploads (0x40), never a download: {frame}"
        );
    }
}

#[test]
fn canopen_scan_json_has_the_identity_and_the_matches() {
    let swd = path("ezwheel-swd");
    let can = format!("candump:exec:{BIN} sim {swd} --can candump:stdio --node-id 12");
    let output = scan(&[
        "--can",
        &can,
        "--timeout-ms",
        "3000",
        "--json",
        "--description",
        &swd,
    ]);
    let out = text(&output.stdout);
    let node: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(node["node"], 12);
    assert_eq!(node["vendor_id"], 0x515);
    assert_eq!(node["matches"], serde_json::json!(["ez-Wheel SWD"]));
}

/// Every parameter's raw value, to show a scan changed nothing.
fn snapshot(sim: &Simulator) -> Vec<Option<i128>> {
    sim.with(|drive| {
        let store = drive.store();
        let names: Vec<String> = store
            .device()
            .parameters
            .iter()
            .map(|p| p.name.clone())
            .collect();
        names
            .iter()
            .map(|n| store.id(n).and_then(|id| store.int(id)))
            .collect()
    })
}

#[test]
fn modbus_tcp_scan_probes_a_unit_range_and_matches_identity_registers() {
    let lafert = Simulator::load(description("lafert-smartris")).unwrap();
    let lenze = Simulator::load(description("lenze-smd")).unwrap();
    let foreign = Simulator::load(description("lafert-smartris")).unwrap();
    foreign.preset("fw_release", 226).unwrap(); // firmware 2.2.6, the manual's example
    let before: Vec<_> = [&lafert, &lenze, &foreign].map(snapshot).into();
    let units = Units::new([
        (UnitId(3), lafert.clone()),
        (UnitId(7), lenze.clone()),
        (UnitId(9), foreign.clone()),
    ]);
    let server = TcpServer::gateway(units, "127.0.0.1:0").unwrap();
    let addr = server.local_addr().to_string();
    let common = ["--units", "1-12", "--timeout-ms", "200"];
    let out = text(&scan(&[&["--modbus-tcp", addr.as_str()][..], &common].concat()).stdout);
    assert_eq!(out.lines().count(), 3, "units 3, 7 and 9 only:\n{out}");
    let unit3 = line_of(&out, "unit", 3).unwrap();
    assert!(
        unit3.contains("Lafert Smartris fw_release = 242"),
        "{unit3}"
    );
    assert!(unit3.ends_with(": Lafert Smartris"), "{unit3}");
    let unit7 = line_of(&out, "unit", 7).unwrap();
    assert!(
        unit7.contains("Lenze smd parameter_configuration = 400"),
        "{unit7}"
    );
    assert!(unit7.ends_with(": Lenze smd"), "{unit7}");
    let unit9 = line_of(&out, "unit", 9).unwrap();
    assert!(unit9.contains("fw_release = 226"), "{unit9}");
    assert!(unit9.ends_with(": no match"), "{unit9}");
    let after: Vec<_> = [&lafert, &lenze, &foreign].map(snapshot).into();
    assert_eq!(before, after, "a scan writes nothing");

    let json =
        text(&scan(&[&["--modbus-tcp", addr.as_str(), "--json"][..], &common].concat()).stdout);
    let units: Vec<serde_json::Value> = json
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let foreign = units.iter().find(|u| u["unit"] == 9).unwrap();
    assert_eq!(foreign["matches"], serde_json::json!([]));
    let lafert_probe = foreign["identity"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["parameter"] == "fw_release")
        .unwrap();
    assert_eq!(lafert_probe["raw"], 226);
    assert_eq!(lafert_probe["covered"], false);
    assert_eq!(lafert_probe["expected"], serde_json::json!([242]));
}

#[test]
fn modbus_rtu_scan_finds_the_units_drivegen_sim_serves_on_one_line() {
    let pty = pty_pair();
    let (lafert, lenze) = (path("lafert-smartris"), path("lenze-smd"));
    let child = Command::new(BIN)
        .args(["sim", &lafert, &lenze, "--serial"])
        .arg(&pty.server)
        .args(["--unit", "2", "--unit", "5"])
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut sim = Process::new(child);
    let mut announced = String::new();
    BufReader::new(sim.child_mut().stdout.take().unwrap())
        .read_line(&mut announced)
        .unwrap();
    assert!(announced.contains("unit 2,5"), "{announced}");
    let client = pty.client.to_str().unwrap();
    let out = text(
        &scan(&[
            "--serial",
            client,
            "--units",
            "1-6",
            "--timeout-ms",
            "150",
            "--description",
            &lafert,
            "--description",
            &lenze,
        ])
        .stdout,
    );
    assert_eq!(out.lines().count(), 2, "{out}");
    assert!(
        line_of(&out, "unit", 2)
            .unwrap()
            .ends_with(": Lafert Smartris"),
        "{out}"
    );
    assert!(
        line_of(&out, "unit", 5).unwrap().ends_with(": Lenze smd"),
        "{out}"
    );
}

#[test]
fn a_modbus_scan_needs_a_description_with_an_identity_register() {
    let output = Command::new(BIN)
        .args([
            "scan",
            "--modbus-tcp",
            "127.0.0.1:9",
            "--description",
            &path("kinco-fd"),
        ])
        .output()
        .unwrap();
    assert!(!output.status.success());
    assert!(
        text(&output.stderr).contains("[identity] parameter"),
        "{}",
        text(&output.stderr)
    );
}

#[test]
fn sim_refuses_two_drives_at_one_id_and_presets_for_nobody() {
    let lafert = path("lafert-smartris");
    let run = |args: &[&str]| {
        let output = Command::new(BIN).arg("sim").args(args).output().unwrap();
        assert!(!output.status.success(), "{args:?} must be refused");
        text(&output.stderr)
    };
    let twice = run(&[&lafert, &path("lenze-smd"), "--modbus-tcp", "127.0.0.1:0"]);
    assert!(twice.contains("two drives at id 1"), "{twice}");
    let nobody = run(&[
        &lafert,
        "--modbus-tcp",
        "127.0.0.1:0",
        "--unit",
        "2",
        "--set",
        "9:fw_release=1",
    ]);
    assert!(nobody.contains("no drive at that id"), "{nobody}");
    let pairs = run(&[
        &lafert,
        &lafert,
        &lafert,
        "--modbus-tcp",
        "127.0.0.1:0",
        "--unit",
        "2",
        "--unit",
        "3",
    ]);
    assert!(pairs.contains("give one id per description"), "{pairs}");
}

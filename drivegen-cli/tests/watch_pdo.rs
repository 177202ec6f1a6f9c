//! `drivegen watch --pdo` end to end against the simulated ez-Wheel SWD (at SYNC) and Kinco FD
//! (by event timer) over CANopen (candump lines over TCP through socat, so the simulated drive
//! outlives the CLI and every frame on the bus is recorded): the values arrive by TPDO, no SDO
//! frame is on the bus while watching, and after the watch (ended by its count or by SIGINT) the
//! TPDO objects hold what they held before.

use std::io::{BufRead, BufReader};
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::{Arc, Mutex};
use std::thread;
use std::time::Duration;

use drivebus::canopen::can::candump::CandumpBus;
use drivebus::canopen::{CanBus, CanFrame, NodeId};
use drivebus::BusError;
use drivesim::canopen::{nodes, Node, NodeConfig};
use drivesim::Simulator;

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");
/// The SWD's node id out of the box.
const NODE: u8 = 0x10;
/// SDO requests to and answers from the node.
const SDO_IDS: [u16; 2] = [0x600 + NODE as u16, 0x580 + NODE as u16];
const SYNC: u16 = 0x080;

fn description(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../descriptions")
        .join(name)
}

fn swd() -> PathBuf {
    description("ezwheel-swd")
}

/// Every frame on the bus, in order, each with whether the CLI sent it (else the node did).
type Log = Arc<Mutex<Vec<(bool, CanFrame)>>>;

/// A bus that records what passes both ways.
struct Recorded<B> {
    bus: B,
    log: Log,
}

impl<B: CanBus> CanBus for Recorded<B> {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.log.lock().unwrap().push((false, *frame));
        self.bus.send(frame)
    }
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        let frame = self.bus.recv(timeout)?;
        if let Some(frame) = &frame {
            self.log.lock().unwrap().push((true, *frame));
        }
        Ok(frame)
    }
}

/// Serves `sim` as the SWD's node to one CLI run after another, recording the bus; returns the
/// bus options and the log.
fn serve(sim: &Simulator) -> (Vec<String>, Log) {
    serve_as(sim, NODE)
}

/// Serves `sim` as node `id`.
fn serve_as(sim: &Simulator, id: u8) -> (Vec<String>, Log) {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap();
    let sim = sim.clone();
    let log = Log::default();
    let recorded = Arc::clone(&log);
    thread::spawn(move || {
        for stream in listener.incoming() {
            let Ok(stream) = stream else { return };
            let config = NodeConfig {
                node: NodeId(id),
                heartbeat: None,
            };
            let mut node = Node::new(sim.clone(), config, sim.variant());
            let bus = CandumpBus::new(stream.try_clone().unwrap(), stream);
            let mut bus = Recorded {
                bus,
                log: Arc::clone(&recorded),
            };
            // The run ends when the CLI closes the connection.
            let _ = nodes::run(std::slice::from_mut(&mut node), &mut bus);
        }
    });
    let bus = vec![
        "--can".into(),
        format!("candump:exec:socat - TCP:{addr}"),
        "--timeout-ms".into(),
        "10000".into(),
    ];
    (bus, log)
}

/// The simulated SWD with a position to see.
fn simulated() -> Simulator {
    let sim = Simulator::load(swd()).unwrap();
    sim.preset("position_actual_value", 1234).unwrap();
    sim
}

/// The raw values of every TPDO communication and mapping object (1800h-1BFFh) the SWD has.
fn tpdo_objects(sim: &Simulator) -> Vec<(String, Option<i128>)> {
    tpdo_objects_of(sim, &swd())
}

/// The same of the drive `path` describes.
fn tpdo_objects_of(sim: &Simulator, path: &Path) -> Vec<(String, Option<i128>)> {
    let device = drivegen::check(path).device.unwrap();
    let names = device
        .parameters
        .iter()
        .filter(|p| {
            p.canopen
                .iter()
                .any(|a| (0x1800..0x1C00).contains(&a.index))
        })
        .map(|p| p.name.clone());
    sim.with(|drive| {
        let store = drive.store();
        names
            .map(|name| {
                let value = store.id(&name).and_then(|id| store.int(id));
                (name, value)
            })
            .collect()
    })
}

fn watch_args(extra: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = ["watch", swd().to_str().unwrap()]
        .iter()
        .chain(extra)
        .map(|s| s.to_string())
        .collect();
    args.extend(["--pdo", "--start", "--interval-ms", "20"].map(String::from));
    args
}

fn text(output: &Output) -> String {
    format!(
        "stdout:\n{}\nstderr:\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

/// The frames from the first SYNC to the last frame before the SDO traffic that follows the
/// last SYNC (the restore): the watching.
fn while_watching(log: &[CanFrame]) -> &[CanFrame] {
    let first = log.iter().position(|f| f.id() == SYNC).expect("a SYNC");
    let last = log.iter().rposition(|f| f.id() == SYNC).unwrap();
    let end = log[last..]
        .iter()
        .position(|f| SDO_IDS.contains(&f.id()))
        .map_or(log.len(), |i| last + i);
    &log[first..end]
}

#[test]
fn values_arrive_by_pdo_with_no_sdo_while_watching_and_the_tpdo_is_restored() {
    let sim = simulated();
    let before = tpdo_objects(&sim);
    let (bus, log) = serve(&sim);
    let mut args = watch_args(&[
        "position_actual_value",
        "error_register",
        "--count",
        "5",
        "--csv",
    ]);
    args.extend(bus);
    let output = Command::new(BIN).args(&args).output().unwrap();
    assert!(output.status.success(), "{}", text(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    let mut lines = stdout.lines();
    assert_eq!(
        lines.next(),
        Some("time [s],position_actual_value [inc],error_register"),
        "{stdout}"
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 5, "{stdout}");
    for row in &rows {
        assert!(row.ends_with(",1234,(none)"), "{stdout}");
    }
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("TPDO 2 mapped for the watch"), "{stderr}");
    let log: Vec<CanFrame> = log.lock().unwrap().iter().map(|(_, f)| *f).collect();
    let watching = while_watching(&log);
    let syncs = watching.iter().filter(|f| f.id() == SYNC).count();
    let tpdos = watching
        .iter()
        .filter(|f| f.id() == 0x280 + u16::from(NODE))
        .count();
    // SYNCs go out on schedule while answers are on their way: one more may have gone out
    // before the fifth answer came.
    assert!(syncs >= 5, "{watching:?}");
    assert_eq!(tpdos, syncs, "a TPDO 2 per SYNC: {watching:?}");
    let sdo = watching
        .iter()
        .filter(|f| SDO_IDS.contains(&f.id()))
        .count();
    assert_eq!(sdo, 0, "no SDO frame while watching: {watching:?}");
    // The mapping was written before (SDO downloads to 1A01h) and restored after.
    let mapping_writes = log
        .iter()
        .filter(|f| f.id() == SDO_IDS[0] && f.data()[1..3] == [0x01, 0x1A])
        .count();
    assert!(
        mapping_writes >= 4,
        "written and restored: {mapping_writes}"
    );
    assert_eq!(tpdo_objects(&sim), before, "the TPDOs as they were");
}

#[test]
fn sigint_ends_the_watch_and_restores_the_tpdo() {
    let sim = simulated();
    let before = tpdo_objects(&sim);
    let (bus, _log) = serve(&sim);
    let mut args = watch_args(&["position_actual_value", "error_register"]);
    args.extend(bus);
    let mut child = Command::new(BIN)
        .args(&args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdout = BufReader::new(child.stdout.take().unwrap());
    // The header and three samples: the watch is running, the TPDO reprogrammed.
    for _ in 0..4 {
        let mut line = String::new();
        stdout.read_line(&mut line).unwrap();
        assert!(!line.is_empty(), "the watch ended early");
    }
    assert_ne!(tpdo_objects(&sim), before, "TPDO 2 mapped while watching");
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let status = child.wait().unwrap();
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    assert!(status.success(), "{status}: {stderr}");
    assert_eq!(
        tpdo_objects(&sim),
        before,
        "the TPDOs as they were: {stderr}"
    );
}

#[test]
fn a_parameter_that_cannot_be_mapped_is_refused_before_anything_is_written() {
    let sim = simulated();
    let before = tpdo_objects(&sim);
    let (bus, log) = serve(&sim);
    let mut args = watch_args(&["position_actual_value", "controlword", "node_id"]);
    args.extend(bus);
    let output = Command::new(BIN).args(&args).output().unwrap();
    assert!(!output.status.success(), "{}", text(&output));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("controlword: the description lets 6040h:00h be mapped into RPDOs only"),
        "{stderr}"
    );
    assert!(
        stderr.contains("node_id: the description lets 2101h:00h be mapped into no PDO"),
        "{stderr}"
    );
    // The node's boot-up message may be on the bus; nothing from the CLI is.
    let sent = log.lock().unwrap().iter().filter(|(cli, _)| *cli).count();
    assert_eq!(sent, 0, "nothing sent");
    assert_eq!(tpdo_objects(&sim), before);
}

#[test]
fn by_event_timer_no_sync_and_no_sdo_go_out_while_watching() {
    let kinco = description("kinco-fd");
    let sim = Simulator::load(&kinco).unwrap();
    let before = tpdo_objects_of(&sim, &kinco);
    let (bus, log) = serve_as(&sim, 1);
    let output = Command::new(BIN)
        .arg("watch")
        .arg(&kinco)
        .args([
            "statusword",
            "position_actual",
            "--pdo",
            "--event-timer",
            "--start",
        ])
        .args(["--interval-ms", "5", "--count", "4", "--json"])
        .args(bus)
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", text(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    let samples: Vec<serde_json::Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(samples.len(), 4, "{stdout}");
    let statusword = sim.with(|drive| {
        let store = drive.store();
        store.int(store.id("statusword").unwrap()).unwrap()
    });
    for sample in &samples {
        let raw = &sample["values"]["statusword"]["raw"];
        assert_eq!(raw.as_i64().map(i128::from), Some(statusword), "{stdout}");
        assert!(
            sample["values"]["position_actual"]["raw"].is_i64(),
            "{stdout}"
        );
    }
    let log = log.lock().unwrap();
    let from_cli: Vec<CanFrame> = log
        .iter()
        .filter(|(cli, _)| *cli)
        .map(|(_, f)| *f)
        .collect();
    assert!(
        !from_cli.iter().any(|f| f.id() == SYNC),
        "no SYNC by event timer"
    );
    // From the NMT Start to the NMT Enter Pre-Operational, the CLI sends nothing.
    let nmt: Vec<usize> = (0..from_cli.len())
        .filter(|&i| from_cli[i].id() == 0)
        .collect();
    assert_eq!(nmt.len(), 2, "start and back: {from_cli:?}");
    assert_eq!(nmt[1], nmt[0] + 1, "nothing between: {from_cli:?}");
    let tpdos = log.iter().filter(|(_, f)| f.id() == 0x181).count();
    assert!(tpdos >= 4, "TPDO 1 by event timer: {tpdos}");
    assert_eq!(
        tpdo_objects_of(&sim, &kinco),
        before,
        "the TPDOs as they were"
    );
}

/// The SWD's TPDO identifiers do not follow its node id (TPDO 3 is 390h on every node): of two
/// nodes, the second gets a TPDO of its own for the watch.
#[test]
fn two_nodes_with_the_same_tpdo_identifiers_are_watched_apart() {
    let sim = format!(
        "candump:exec:{BIN} sim {} --can candump:stdio --node-id 16 --node-id 17",
        swd().display()
    );
    let output = Command::new(BIN)
        .args(watch_args(&[
            "statusword",
            "position_actual_value",
            "--count",
            "3",
            "--csv",
        ]))
        .args(["--can", &sim, "--node-id", "16", "--node-id", "17"])
        .args(["--timeout-ms", "10000"])
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", text(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    let rows: Vec<&str> = stdout.lines().skip(1).collect();
    assert_eq!(rows.len(), 3, "{stdout}");
    for row in rows {
        assert!(
            row.ends_with(",switch_on_disabled,0,switch_on_disabled,0"),
            "{stdout}"
        );
    }
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("node 17: TPDO 2 mapped for the watch"),
        "{stderr}"
    );
    assert!(
        !stderr.contains("node 16: TPDO"),
        "node 16's TPDO 3 as it is: {stderr}"
    );
}

//! `drivegen trace` on the Kinco manual's own CANopen log: the position sequence of section 11.5
//! (`shared/seeds/003_8cc8f7f4f05b8633.txt`, lines 3266-3273, station 1: SDO requests on 601h
//! and their answers on 581h), each frame named and typed; filters; a trigger window; bad input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

/// Lines 3266-3273 as candump lines, answers as the manual prints them (it echoes the data in
/// each download answer), one line that is not a frame, and a heartbeat of station 1.
const POSITION_SEQUENCE: &str = "\
(1700000000.000000) can0 601#2B4060000F000000
(1700000000.001000) can0 581#604060000F000000
(1700000000.002000) can0 601#2F60600001000000
(1700000000.003000) can0 581#6060600001000000
(1700000000.004000) can0 601#237A600050C30000
(1700000000.005000) can0 581#607A600050C30000
this line is not a frame
(1700000000.006000) can0 601#2B4060002F000000
(1700000000.007000) can0 581#604060002F000000
(1700000000.008000) can0 601#2B4060003F000000
(1700000000.009000) can0 581#604060003F000000
(1700000000.010000) can0 701#05
";

/// The capture in a file of its own (tests run side by side: none may read another's half-written
/// file).
fn capture() -> PathBuf {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let path = std::env::temp_dir().join(format!("drivegen-trace-{}-{n}.log", std::process::id()));
    std::fs::write(&path, POSITION_SEQUENCE).unwrap();
    path
}

fn trace(args: &[&str]) -> Output {
    let description = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/kinco-fd");
    let log = capture();
    let output = Command::new(BIN)
        .arg("trace")
        .arg(description)
        .arg(&log)
        .args(args)
        .output()
        .unwrap();
    std::fs::remove_file(log).unwrap();
    output
}

fn json_lines(output: &Output) -> Vec<Value> {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn the_manuals_position_sequence_is_named_and_typed_past_a_malformed_line() {
    let output = trace(&["--json"]);
    let lines = json_lines(&output);
    assert_eq!(lines.len(), 11, "every frame, the malformed line skipped");
    assert!(
        String::from_utf8_lossy(&output.stderr).contains("skipped 1 malformed line(s)"),
        "counted"
    );
    let writes: Vec<(&str, &Value)> = lines
        .iter()
        .filter(|l| l["kind"] == "sdo →")
        .map(|l| {
            let samples = l["samples"].as_object().unwrap();
            let (name, value) = samples.iter().next().unwrap();
            (name.as_str(), value)
        })
        .collect();
    assert_eq!(
        writes,
        [
            ("controlword", &Value::from(15.0)),
            ("modes_of_operation", &Value::from(1.0)),
            ("target_position", &Value::from(50_000.0)),
            ("controlword", &Value::from(47.0)),
            ("controlword", &Value::from(63.0)),
        ]
    );
    let mode = lines
        .iter()
        .find(|l| l["object"] == "write modes_of_operation");
    assert_eq!(mode.unwrap()["value"], "position", "the enumeration's name");
    assert_eq!(lines[1]["object"], "controlword written");
    assert_eq!(lines[10]["kind"], "heartbeat");
}

#[test]
fn a_trigger_keeps_its_window_and_filters_keep_what_is_asked() {
    // Controlword above 0x2E: the 2Fh write (line 3271) after 0Fh.
    let lines = json_lines(&trace(&[
        "--trigger",
        "controlword>0x2E",
        "--pre",
        "1",
        "--post",
        "2",
        "--json",
    ]));
    let at: Vec<(&str, &str)> = lines
        .iter()
        .map(|l| (l["at"].as_str().unwrap(), l["time"].as_str().unwrap()))
        .collect();
    assert_eq!(
        at,
        [
            ("before", "1700000000.005000"),
            ("trigger", "1700000000.006000"),
            ("after", "1700000000.007000"),
            ("after", "1700000000.008000"),
        ]
    );
    assert!(lines.iter().all(|l| l["window"] == 1));

    let csv = trace(&["--parameter", "target_position", "--csv"]);
    let text = String::from_utf8_lossy(&csv.stdout);
    let rows: Vec<&str> = text.lines().collect();
    assert_eq!(rows[0], "window,at,time,node,kind,object,value");
    assert_eq!(
        rows[1..],
        [",,1700000000.004000,1,sdo →,write target_position,target_position=50000 inc"]
    );
    let other_node = json_lines(&trace(&["--node", "2", "--json"]));
    assert!(other_node.is_empty(), "station 2 sent nothing");
}

#[test]
fn a_bad_trigger_or_parameter_is_refused_with_the_reason() {
    let bad = trace(&["--trigger", "controlword>fast"]);
    assert!(!bad.status.success());
    assert!(
        String::from_utf8_lossy(&bad.stderr).contains("write NAME>LEVEL"),
        "{}",
        String::from_utf8_lossy(&bad.stderr)
    );
    let unknown = trace(&["--trigger", "controlwort>1"]);
    assert!(String::from_utf8_lossy(&unknown.stderr).contains("did you mean `controlword`"));
}

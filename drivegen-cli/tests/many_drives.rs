//! `read` and `watch` with a repeated `--unit` / `--node-id` (issue 31 item 4): several drives on
//! one bus, one table with a column per drive; a drive that fails shows its error in its column,
//! the others still show, and the exit code says whether every drive answered. Against the
//! simulator: Lafert drives behind one Modbus TCP gateway, ez-Wheel SWD nodes on one CAN bus
//! (read at once through the network manager: missing nodes cost one timeout together).

use std::path::Path;
use std::process::Output;

use drivebus::modbus::UnitId;
use drivesim::modbus::tcp::TcpServer;
use drivesim::modbus::Units;
use drivesim::Simulator;

mod support;

use support::{drivegen, stderr, stdout, BIN};

fn description(family: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../descriptions")
        .join(family);
    path.to_str().unwrap().to_owned()
}

/// Lafert drives at units 3 and 7 behind one gateway, with DC links of 49.50 V and 41.00 V.
fn gateway() -> (TcpServer, String) {
    let drive = |volts| {
        let sim = Simulator::load(description("lafert-smartris")).unwrap();
        sim.preset("bus_dc_link", volts).unwrap();
        sim
    };
    let units = Units::new([(UnitId(3), drive(4950)), (UnitId(7), drive(4100))]);
    let server = TcpServer::gateway(units, "127.0.0.1:0").unwrap();
    let addr = server.local_addr().to_string();
    (server, addr)
}

/// `command` (read, watch) of the Lafert description's `parameters` at `units` behind `addr`.
fn at_units(
    command: &str,
    parameters: &[&str],
    addr: &str,
    units: &[&str],
    extra: &[&str],
) -> Output {
    let lafert = description("lafert-smartris");
    let mut args = vec![command, &lafert];
    args.extend(parameters);
    args.extend(["--modbus-tcp", addr, "--timeout-ms", "500"]);
    for unit in units {
        args.extend(["--unit", unit]);
    }
    args.extend(extra);
    drivegen(&args)
}

/// `read` of the Lafert description's DC link and status at `units` behind `addr`.
fn read_units(addr: &str, units: &[&str], extra: &[&str]) -> Output {
    at_units("read", &["bus_dc_link", "drive_status"], addr, units, extra)
}

/// Two polls of the Lafert description's DC link at `units` behind `addr`.
fn watch_units(addr: &str, units: &[&str], extra: &[&str]) -> Output {
    let polls = [&["--count", "2", "--interval-ms", "10"], extra].concat();
    at_units("watch", &["bus_dc_link"], addr, units, &polls)
}

/// The cells of the table row whose first cell is `name`, split on runs of two spaces.
fn row<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
    let line = text
        .lines()
        .find(|l| l.split("  ").next() == Some(name))
        .unwrap_or_else(|| panic!("no row {name}:\n{text}"));
    line.split("  ")
        .map(str::trim)
        .filter(|c| !c.is_empty())
        .collect()
}

#[test]
fn read_shows_a_column_per_unit() {
    let (_server, addr) = gateway();
    let output = read_units(&addr, &["7", "3"], &[]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert_eq!(row(&text, "parameter"), ["parameter", "unit 7", "unit 3"]);
    assert_eq!(
        row(&text, "bus_dc_link"),
        ["bus_dc_link", "41.00 V", "49.50 V"]
    );
    assert_eq!(
        row(&text, "drive_status"),
        ["drive_status", "standby", "standby"]
    );
}

#[test]
fn a_unit_that_does_not_answer_shows_its_error_and_fails_the_command() {
    let (_server, addr) = gateway();
    let output = read_units(&addr, &["3", "9", "7"], &[]);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    let text = stdout(&output);
    let dc_link = row(&text, "bus_dc_link");
    assert_eq!(dc_link[..2], ["bus_dc_link", "49.50 V"], "{text}");
    assert!(
        dc_link[2].starts_with("error: ") && dc_link[2].contains("unit 9 (timeout)"),
        "{text}"
    );
    assert_eq!(dc_link[3], "41.00 V", "{text}");
    assert_eq!(
        row(&text, "drive_status"),
        ["drive_status", "standby", "-", "standby"]
    );
    assert!(
        stderr(&output).contains("1 of 3 drives failed"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn read_json_has_an_object_per_unit() {
    let (_server, addr) = gateway();
    let output = read_units(&addr, &["3", "9"], &["--json"]);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    let json: serde_json::Value = serde_json::from_str(&stdout(&output)).unwrap();
    assert_eq!(json[0]["unit"], 3);
    assert_eq!(json[0]["values"][0]["parameter"], "bus_dc_link");
    assert_eq!(json[0]["values"][0]["raw"], 4950);
    assert_eq!(json[1]["unit"], 9);
    assert!(
        json[1]["error"].as_str().unwrap().contains("timeout"),
        "{json}"
    );
    assert!(json[1].get("values").is_none());
}

#[test]
fn watch_polls_every_unit_and_keeps_going_when_one_fails() {
    let (_server, addr) = gateway();
    let output = watch_units(&addr, &["3", "9", "7"], &[]);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    let text = stdout(&output);
    let header: Vec<&str> = text.lines().next().unwrap().split_whitespace().collect();
    assert_eq!(
        header,
        ["time", "parameter", "unit", "3", "unit", "9", "unit", "7"]
    );
    let polls: Vec<&str> = text.lines().filter(|l| l.contains("bus_dc_link")).collect();
    assert_eq!(polls.len(), 2, "{text}");
    for poll in polls {
        assert!(
            poll.contains("49.50 V") && poll.contains("41.00 V"),
            "{poll}"
        );
        assert!(
            poll.contains("error: ") && poll.contains("unit 9"),
            "{poll}"
        );
    }
    assert!(stderr(&output).contains("1 of 3 drives failed"));
}

#[test]
fn watch_json_has_every_unit_in_each_poll() {
    let (_server, addr) = gateway();
    let output = watch_units(&addr, &["3", "7"], &["--json"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let polls: Vec<serde_json::Value> = stdout(&output)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(polls.len(), 2);
    for poll in polls {
        assert_eq!(poll["drives"][0]["unit"], 3);
        assert_eq!(poll["drives"][0]["values"]["bus_dc_link"]["raw"], 4950);
        assert_eq!(poll["drives"][1]["unit"], 7);
        assert_eq!(poll["drives"][1]["values"]["bus_dc_link"]["raw"], 4100);
    }
}

#[test]
fn read_shows_a_column_per_canopen_node_and_the_missing_one_fails() {
    let swd = description("ezwheel-swd");
    let can = format!(
        "candump:exec:{BIN} sim {swd} --can candump:stdio --node-id 4 --node-id 5 --set 5:vendor_id=0x1234"
    );
    let read = |nodes: &[&str]| {
        // A long timeout: the first request goes out while the simulated nodes' process may
        // still be loading its description (README: give a started relay time to listen).
        let mut args = vec![
            "read",
            &swd,
            "vendor_id",
            "--can",
            &can,
            "--timeout-ms",
            "3000",
        ];
        for node in nodes {
            args.extend(["--node-id", node]);
        }
        drivegen(&args)
    };
    let both = read(&["4", "5"]);
    assert!(both.status.success(), "{}{}", stdout(&both), stderr(&both));
    let text = stdout(&both);
    assert_eq!(row(&text, "parameter"), ["parameter", "node 4", "node 5"]);
    let vendor = row(&text, "vendor_id");
    assert_eq!(vendor.len(), 3, "{text}");
    assert_ne!(
        vendor[1], vendor[2],
        "each node answered for itself: {text}"
    );
    assert!(
        vendor[2].contains("4660") || vendor[2].contains("1234"),
        "{text}"
    );

    let one_missing = read(&["4", "6"]);
    assert_eq!(
        one_missing.status.code(),
        Some(1),
        "{}",
        stderr(&one_missing)
    );
    let text = stdout(&one_missing);
    let vendor = row(&text, "vendor_id");
    assert_eq!(vendor[1], row(&stdout(&both), "vendor_id")[1], "{text}");
    assert!(
        vendor[2].starts_with("error: ") && vendor[2].contains("node 6"),
        "{text}"
    );
}

#[test]
fn canopen_nodes_are_read_at_once_so_missing_nodes_cost_one_timeout() {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../drivesim/tests/fixtures/network_node.toml")
        .display()
        .to_string();
    let can =
        format!("candump:exec:{BIN} sim {fixture} --can candump:stdio --node-id 1 --node-id 2");
    const TIMEOUT_MS: u64 = 1500;
    let timeout = TIMEOUT_MS.to_string();
    let mut args = vec![
        "read",
        &fixture,
        "setpoint",
        "--can",
        &can,
        "--timeout-ms",
        &timeout,
    ];
    // Two nodes answer, four do not: one after the other that would take four timeouts.
    for node in ["1", "2", "7", "8", "9", "10"] {
        args.extend(["--node-id", node]);
    }
    let started = std::time::Instant::now();
    let read = drivegen(&args);
    let took = started.elapsed();
    assert_eq!(read.status.code(), Some(1), "{}", stderr(&read));
    let text = stdout(&read);
    let setpoint = row(&text, "setpoint");
    assert!(
        setpoint[1].starts_with("100") && setpoint[2].starts_with("100"),
        "{text}"
    );
    assert!(
        setpoint[3..].iter().all(|cell| cell.starts_with("error: ")),
        "{text}"
    );
    assert!(
        took < std::time::Duration::from_millis(3 * TIMEOUT_MS),
        "four missing nodes took {took:?}: not read at once"
    );
}

#[test]
fn one_drive_commands_refuse_a_repeated_id_and_nobody_takes_one_id_twice() {
    let (_server, addr) = gateway();
    let lafert = description("lafert-smartris");
    let write = drivegen(&[
        "write",
        &lafert,
        "speed_setpoint",
        "100",
        "--modbus-tcp",
        &addr,
        "--unit",
        "3",
        "--unit",
        "7",
    ]);
    assert_eq!(write.status.code(), Some(1));
    assert!(
        stderr(&write).contains("talks to one drive"),
        "{}",
        stderr(&write)
    );
    let twice = read_units(&addr, &["3", "3"], &[]);
    assert_eq!(twice.status.code(), Some(1));
    assert!(
        stderr(&twice).contains("--unit 3 is given twice"),
        "{}",
        stderr(&twice)
    );
}

//! `drivegen network boot` and `network status` end to end against `drivegen sim` serving
//! several nodes on one candump stdio bus: a booted node, a foreign one and a missing one
//! reported each on its line (exit code 1), the same again on a second boot; the status of the
//! nodes with their heartbeat state; and bad network files refused with the file and line
//! before the bus is opened.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn fixture() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../drivesim/tests/fixtures/network_node.toml")
        .display()
        .to_string()
}

fn drivegen(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

/// A fresh folder for this test's files.
fn folder(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("drivegen-network-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes the network file `text` (with `FIXTURE` replaced by the fixture's path, `KINCO` by
/// the Kinco description's).
fn network_file(test: &str, text: &str) -> String {
    let path = folder(test).join("net.toml");
    let kinco = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/kinco-fd");
    let text = text
        .replace("FIXTURE", &fixture())
        .replace("KINCO", &kinco.display().to_string());
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// The simulated nodes 1 (product code 7) and 2 (product code 8) on a candump stdio bus.
fn simulated() -> String {
    format!(
        "candump:exec:{BIN} sim {} --can candump:stdio --node-id 1 --node-id 2 \
         --set vendor_id=0x0DD0 --set 1:product_code=7 --set 2:product_code=8",
        fixture()
    )
}

const NETWORK: &str = r#"format = 1

[[node]]
id = 1
description = "FIXTURE"
identity = { vendor_id = 0x0DD0, product_code = 7 }
heartbeat_ms = 100
parameters = { setpoint = "1500 rpm" }

[[node]]
id = 2
description = "FIXTURE"
identity = { vendor_id = 0x0DD0, product_code = 7 }

[[node]]
id = 3
description = "FIXTURE"
"#;

#[test]
fn a_network_boots_and_every_node_is_reported_on_its_line() {
    let file = network_file("boot", NETWORK);
    let can = simulated();
    let boot = || {
        drivegen(&[
            "network",
            "boot",
            &file,
            "--can",
            &can,
            "--timeout-ms",
            "500",
        ])
    };
    let first = boot();
    let out = String::from_utf8_lossy(&first.stdout).into_owned();
    assert_eq!(first.status.code(), Some(1), "{out}");
    assert_eq!(
        out.lines().collect::<Vec<_>>(),
        [
            "node   1 (Network Node): booted, 2 written, 0 unchanged, started",
            "node   2 (Network Node): foreign identity: 1018h sub 2 is 0x00000008, expected 0x00000007; left alone",
            "node   3 (Network Node): no answer to the probe: not on the bus; left alone",
        ]
    );
    assert!(String::from_utf8_lossy(&first.stderr).contains("2 of 3 node(s) not booted"));
    let again = boot();
    assert_eq!(
        String::from_utf8_lossy(&again.stdout),
        out,
        "booting again changes nothing"
    );
}

#[test]
fn status_lists_the_nodes_with_their_heartbeat_state() {
    let can = format!(
        "candump:exec:{BIN} sim {} --can candump:stdio --node-id 1 --node-id 2 \
         --set vendor_id=0x0DD0 --set 1:producer_heartbeat_time=100",
        fixture()
    );
    let status = drivegen(&[
        "network",
        "status",
        "--can",
        &can,
        "--timeout-ms",
        "300",
        "--listen-ms",
        "600",
    ]);
    let out = String::from_utf8_lossy(&status.stdout);
    assert!(status.status.success(), "{out}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    assert!(
        lines[0].starts_with("node   1: device type 0x00000000, vendor-ID 0x00000dd0"),
        "{out}"
    );
    assert!(
        lines[0].ends_with("NMT PreOperational, last EMCY none"),
        "{out}"
    );
    assert!(lines[1].contains("NMT no heartbeat"), "{out}");
}

#[test]
fn bad_network_files_are_refused_with_the_file_and_line() {
    let cases = [
        (
            "unknown_description",
            "format = 1\n[[node]]\nid = 1\ndescription = \"no-such-drive\"\n",
            ":2: node 1: description ",
        ),
        (
            "unknown_parameter",
            "format = 1\n[[node]]\nid = 1\ndescription = \"FIXTURE\"\nparameters = { spead = 1 }\n",
            ":5: node 1: spead: no such parameter in Network Node",
        ),
        (
            "read_only",
            "format = 1\n[[node]]\nid = 1\ndescription = \"FIXTURE\"\nparameters = { measured = 1 }\n",
            ":5: node 1: measured: not writable over CANopen",
        ),
        (
            "out_of_range",
            "format = 1\n[[node]]\nid = 1\ndescription = \"FIXTURE\"\n\n[node.parameters]\nsetpoint = \"9000 rpm\"\n",
            ":7: node 1: setpoint: ",
        ),
        (
            "absent_pdo",
            "format = 1\n[[node]]\nid = 1\ndescription = \"FIXTURE\"\n[[node.tpdo]]\nnumber = 1\nmapping = [\"setpoint\"]\n",
            ":5: node 1: the drive has no TPDO 1: its description has no object 1800h",
        ),
        (
            "unmappable",
            "format = 1\n[[node]]\nid = 1\ndescription = \"KINCO\"\n[[node.tpdo]]\nnumber = 1\nmapping = [\n  \"statusword\",\n  \"profile_speed\",\n]\n",
            ":9: node 1: PDO mapping: `profile_speed` cannot be mapped into a TPDO",
        ),
        (
            "duplicate",
            "format = 1\n[[node]]\nid = 1\ndescription = \"FIXTURE\"\n[[node]]\nid = 1\ndescription = \"FIXTURE\"\n",
            ":5: node 1 appears twice",
        ),
    ];
    for (test, text, expected) in cases {
        let file = network_file(test, text);
        // The bus is never opened: the interface does not exist.
        let refused = drivegen(&["network", "boot", &file, "--can", "socketcan:nosuchcan9"]);
        let err = String::from_utf8_lossy(&refused.stderr);
        assert_eq!(refused.status.code(), Some(1), "{test}: {err}");
        assert!(err.contains(&format!("{file}{expected}")), "{test}: {err}");
        assert!(err.contains("(nothing was sent)"), "{test}: {err}");
        let _ = std::fs::remove_dir_all(folder(test));
    }
}

#[test]
fn a_boot_configures_the_pdos_of_the_file() {
    let file = network_file(
        "pdo",
        "format = 1\n[[node]]\nid = 1\ndescription = \"KINCO\"\n\
         [[node.tpdo]]\nnumber = 1\ntransmission_type = 254\nevent_timer = 50\n\
         mapping = [\"statusword\", \"modes_of_operation_display\"]\n",
    );
    let kinco = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/kinco-fd");
    let can = format!(
        "candump:exec:{BIN} sim {} --can candump:stdio --node-id 1",
        kinco.display()
    );
    // 10 s: the simulator loads its description while the first request waits.
    let boot = drivegen(&[
        "network",
        "boot",
        &file,
        "--can",
        &can,
        "--timeout-ms",
        "10000",
    ]);
    let out = String::from_utf8_lossy(&boot.stdout);
    assert!(
        boot.status.success(),
        "{out}{}",
        String::from_utf8_lossy(&boot.stderr)
    );
    assert!(
        out.trim_end()
            .ends_with("booted, 1 written, 0 unchanged, started"),
        "the TPDO written: {out}"
    );
}

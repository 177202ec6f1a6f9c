//! `drivegen lss` against simulated SWDs (`drivegen sim --can candump:stdio`, started by the
//! command itself through `candump:exec:`): Fastscan finds two drives without a node id and gives
//! them ids 20 and 21; inquire shows the identity matched against the descriptions; a node id
//! no node may have is refused before the bus is opened; a bit rate the drive refuses is
//! reported with its error code.

use std::path::Path;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn swd() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/ezwheel-swd");
    path.to_str().unwrap().to_owned()
}

fn drivegen(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A `--can` backend running simulated SWDs with `sim_args`.
fn simulated(sim_args: &str) -> String {
    format!(
        "candump:exec:{BIN} sim {} --can candump:stdio {sim_args}",
        swd()
    )
}

#[test]
fn fastscan_finds_two_unconfigured_drives_and_gives_them_ids_20_and_21() {
    let can = simulated(
        "--node-id 1 --node-id 2 --lss-unconfigured --set 1:serial_number=0xB02 --set 2:serial_number=0xA01",
    );
    // Steps of 100 ms: the simulator answers through two pipes on a shared machine.
    let scan = [
        "lss",
        "scan",
        "--assign",
        "20",
        "--step-ms",
        "100",
        "--timeout-ms",
        "3000",
    ];
    let output = drivegen(&[&scan[..], &["--can", &can]].concat());
    let (out, err) = (text(&output.stdout), text(&output.stderr));
    assert!(output.status.success(), "{out}\n{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}\n{err}");
    assert!(
        lines[0].starts_with("node  20: vendor-ID 0x00000515"),
        "{out}"
    );
    assert!(
        lines[0].contains("serial 0x00000a01: ez-Wheel SWD"),
        "{out}"
    );
    assert!(lines[1].starts_with("node  21:"), "{out}");
    assert!(lines[1].contains("serial 0x00000b02"), "{out}");
    assert!(
        err.contains("2 node(s) without a node id answered"),
        "{err}"
    );
}

#[test]
fn inquire_shows_the_identity_and_node_id_matched_against_the_descriptions() {
    let can = simulated("--set serial_number=42");
    let output = drivegen(&["lss", "inquire", "--timeout-ms", "3000", "--can", &can]);
    let out = text(&output.stdout);
    assert!(output.status.success(), "{out}\n{}", text(&output.stderr));
    assert_eq!(
        out.trim(),
        "node  16: vendor-ID 0x00000515, product code 0x00000000, revision 0x00000000, serial 0x0000002a: ez-Wheel SWD"
    );
}

#[test]
fn node_ids_0_and_128_to_254_are_refused_before_the_bus_is_opened() {
    for id in ["0", "128", "254"] {
        for command in [
            &["lss", "set-node-id", id][..],
            &["lss", "scan", "--assign", id],
        ] {
            let args = [command, &["--can", "candump:exec:/nonexistent/drivegen"]].concat();
            let output = drivegen(&args);
            let err = text(&output.stderr);
            assert!(!output.status.success());
            assert!(
                err.contains(&format!("node id {id} cannot be configured")),
                "{args:?}: {err}"
            );
        }
    }
}

#[test]
fn a_bit_rate_the_drive_refuses_is_reported_with_its_error_code() {
    let can = simulated("");
    let output = drivegen(&[
        "lss",
        "set-bitrate",
        "100k",
        "--timeout-ms",
        "3000",
        "--can",
        &can,
    ]);
    let err = text(&output.stderr);
    assert!(!output.status.success());
    assert!(
        err.contains("the node does not support this bit rate (code 1)"),
        "{err}"
    );
    let output = drivegen(&[
        "lss",
        "set-bitrate",
        "250k",
        "--timeout-ms",
        "3000",
        "--can",
        &can,
    ]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    assert!(text(&output.stdout).contains("bit rate 250000 bit/s configured"));
}

#[test]
fn only_lss_slaves_start_unconfigured() {
    let lafert = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions/lafert-smartris");
    let output = drivegen(&[
        "sim",
        lafert.to_str().unwrap(),
        "--can",
        "candump:stdio",
        "--lss-unconfigured",
    ]);
    let err = text(&output.stderr);
    assert!(!output.status.success());
    assert!(err.contains("is not an LSS slave"), "{err}");
}

//! `drivegen safety signature` end to end on the SRDO fixture (the SWD's default SRDO1, SRDO2,
//! SRDO10): the manual's 13FFh values (lines 3588, 3589) and the quick start's BABDh (line 4111).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use drivebus::canopen::pdo::MappedObject;
use drivebus::canopen::srdo::{signature, SrdoCommunication, SrdoConfig, SrdoDirection};

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../codegen/tests/fixtures/srdo")
}

fn drivegen(args: &[&str]) -> Output {
    let fixture = fixture();
    let mut all = vec!["safety", "signature", fixture.to_str().unwrap()];
    all.extend_from_slice(args);
    Command::new(BIN).args(all).output().unwrap()
}

fn stdout(output: &Output) -> String {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout).trim().to_owned()
}

#[test]
fn srdo1_default_signature_at_the_default_node_id() {
    assert_eq!(stdout(&drivegen(&["--srdo", "1"])), "0x70AB");
}

#[test]
fn quick_start_disabled_srdo1() {
    assert_eq!(
        stdout(&drivegen(&["--srdo", "1", "--set", "direction=0"])),
        "0xBABD"
    );
    assert_eq!(
        stdout(&drivegen(&["--srdo", "1", "--set", "direction=invalid"])),
        "0xBABD"
    );
}

#[test]
fn a_described_communication_object_can_be_set_by_name() {
    // The fixture describes 1301h sub 1 as `srdo1_information_direction`.
    assert_eq!(
        stdout(&drivegen(&[
            "--srdo",
            "1",
            "--set",
            "srdo1_information_direction=0"
        ])),
        "0xBABD"
    );
    let refused = drivegen(&["--srdo", "2", "--set", "srdo1_information_direction=0"]);
    assert!(!refused.status.success(), "1301h is not SRDO 2's");
}

#[test]
fn another_node_id_moves_srdo1_cob_ids() {
    let mapping = [
        MappedObject::from_entry(0x6620_0108),
        MappedObject::from_entry(0x6622_0108),
    ];
    let expected = signature(&SrdoConfig {
        number: 1,
        communication: SrdoCommunication {
            direction: SrdoDirection::Receive,
            sct_ms: 50,
            srvt_ms: 20,
            transmission_type: 0xFE,
            cob_id_normal: 0xFF + 2 * 3,
            cob_id_inverted: 0x100 + 2 * 3,
        },
        mapping: &mapping,
    })
    .unwrap();
    assert_ne!(expected, 0x70AB);
    assert_eq!(
        stdout(&drivegen(&["--srdo", "1", "--node-id", "3"])),
        format!("{expected:#06X}")
    );
}

#[test]
fn json_carries_the_signature_and_the_configuration() {
    let text = stdout(&drivegen(&["--srdo", "2", "--json"]));
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["signature"], "0x8C5F");
    assert_eq!(json["signature_value"], 0x8C5F);
    assert_eq!(
        json["configuration"]["mapping"].as_array().unwrap().len(),
        16
    );
    assert_eq!(json["configuration"]["cob_id_normal"], 0x103);
}

#[test]
fn mapping_entries_can_be_changed() {
    let changed = stdout(&drivegen(&["--srdo", "1", "--set", "entry.2=0x66220208"]));
    assert_ne!(changed, "0x70AB");
}

#[test]
fn bad_requests_are_refused() {
    for args in [
        &["--srdo", "9"][..],
        &["--srdo", "1", "--set", "sct"],
        &["--srdo", "1", "--set", "nothing=1"],
        &["--srdo", "1", "--set", "srvt_ms=300"],
        &["--srdo", "1", "--set", "entry.3=1"],
        &["--srdo", "1", "--set", "direction=7"],
    ] {
        let output = drivegen(args);
        assert!(!output.status.success(), "{args:?} was accepted");
        assert!(!output.stderr.is_empty());
    }
}

use super::*;
use crate::ir::Direction;

const FILE: &str = r#"format = 1

[[node]]
id = 5
description = "../descriptions/lafert-smartris"
heartbeat_ms = 100
identity = { vendor_id = 0x0DD0, product_code = 7 }
parameters = { speed_ramp_up = "2000 ms", operation_mode = "velocity", limit = 12 }

[[node]]
id = 6
description = "/abs/kinco-fd"
start = false
"#;

#[test]
fn a_network_file_is_read_with_its_lines_and_order() {
    let file = parse(FILE).unwrap();
    let [five, six] = &file.nodes[..] else {
        panic!("two nodes: {file:?}");
    };
    assert_eq!(
        (five.id, five.line, five.heartbeat_ms, five.start),
        (5, 3, Some(100), true)
    );
    assert_eq!(five.identity.vendor_id, Some(0x0DD0));
    assert_eq!(five.identity.revision, None);
    let names: Vec<_> = five
        .parameters
        .iter()
        .map(|p| (p.name.as_str(), p.value.as_str(), p.line))
        .collect();
    assert_eq!(
        names,
        [
            ("speed_ramp_up", "2000 ms", 8),
            ("operation_mode", "velocity", 8),
            ("limit", "12", 8)
        ]
    );
    assert_eq!((six.id, six.start, six.line), (6, false, 10));
}

fn refused(text: &str) -> NetworkFileError {
    parse(text).expect_err("refused")
}

#[test]
fn bad_files_are_refused_with_the_line() {
    let bad_id = refused("format = 1\n[[node]]\nid = 128\ndescription = \"x\"\n");
    assert_eq!(
        (bad_id.line, bad_id.kind),
        (Some(3), NetworkFileErrorKind::NodeIdOutOfRange(128))
    );
    let twice = refused(
        "format = 1\n[[node]]\nid = 3\ndescription = \"x\"\n[[node]]\nid = 3\ndescription = \"y\"\n",
    );
    assert_eq!(twice.kind, NetworkFileErrorKind::DuplicateNode(3));
    assert_eq!(twice.line, Some(5));
    assert_eq!(
        refused("format = 2\n").kind,
        NetworkFileErrorKind::UnsupportedFormat(2)
    );
    assert_eq!(refused("format = 1\n").kind, NetworkFileErrorKind::NoNodes);
    let unknown = refused("format = 1\n[[node]]\nid = 1\ndescription = \"x\"\npdo = 3\n");
    assert!(matches!(unknown.kind, NetworkFileErrorKind::Syntax(_)));
    assert_eq!(unknown.line, Some(5));
    let heartbeat =
        refused("format = 1\n[[node]]\nid = 1\ndescription = \"x\"\nheartbeat_ms = 70000\n");
    assert_eq!(heartbeat.line, Some(5));
    let vendor = refused(
        "format = 1\n[[node]]\nid = 1\ndescription = \"x\"\nidentity = { vendor_id = -1 }\n",
    );
    assert_eq!(vendor.line, Some(5));
    assert!(refused("format = 1\n[[node]]\nid = 1\n")
        .to_string()
        .contains("description"));
    let cut = refused("format = 1\n[[node]]\nid = 1\ndescription = \"x");
    assert!(matches!(cut.kind, NetworkFileErrorKind::Syntax(_)));
}

/// A network file with one Kinco node (id 5) and `pdos` as its PDO tables (from line 5 on).
fn with_pdos(pdos: &str) -> NetworkFile {
    parse(&format!(
        "format = 1\n[[node]]\nid = 5\ndescription = \"kinco\"\n{pdos}"
    ))
    .expect("read")
}

fn kinco() -> crate::ir::Device {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/kinco-fd");
    crate::check(path.as_ref())
        .device
        .expect("the Kinco description")
}

fn pdo_refusal(device: &crate::ir::Device, pdos: &str) -> NetworkFileError {
    let file = with_pdos(pdos);
    check_pdos(&file.nodes[0], device).expect_err("refused")
}

#[test]
fn pdos_are_read_and_checked_against_the_description() {
    let file = with_pdos(
        "[[node.rpdo]]\nnumber = 2\nmapping = [\"target_velocity\"]\n\
         [[node.tpdo]]\nnumber = 1\ntransmission_type = 254\nevent_timer = 20\n\
         mapping = [\"statusword\",\n  \"modes_of_operation_display\"]\n",
    );
    let pdos = &file.nodes[0].pdos;
    assert_eq!(pdos.len(), 2);
    assert_eq!(
        (pdos[0].direction, pdos[0].line),
        (Direction::Tx, 8),
        "TPDOs first"
    );
    assert_eq!(pdos[0].mapping[1].line, 13);
    let checked = check_pdos(&file.nodes[0], &kinco()).unwrap();
    assert_eq!(
        (
            checked[0].cob_id,
            checked[0].event_timer,
            checked[0].transmission_type
        ),
        (0x185, Some(20), Some(254)),
        "the predefined connection set's COB-ID"
    );
    assert_eq!(
        checked[0].entries,
        [
            drivebus_model::canopen::MappedObject::new(0x6041, 0, 16),
            drivebus_model::canopen::MappedObject::new(0x6061, 0, 8)
        ]
    );
    assert_eq!(
        (checked[1].kind, checked[1].cob_id),
        (drivebus_model::canopen::PdoKind::Receive, 0x305)
    );
}

#[test]
fn a_pdo_the_drive_cannot_take_is_refused_with_the_line_and_why() {
    let kinco = kinco();
    let cases: [(&str, u32, NetworkFileErrorKind); 7] = [
        (
            "[[node.tpdo]]\nnumber = 2\nmapping = [\"statusword\"]\n",
            5,
            NetworkFileErrorKind::PdoAbsent {
                pdo: "TPDO 2".into(),
                index: 0x1801,
            },
        ),
        (
            "[[node.rpdo]]\nnumber = 1\nevent_timer = 10\nmapping = []\n",
            5,
            NetworkFileErrorKind::PdoSettingAbsent {
                pdo: "RPDO 1".into(),
                key: "event_timer",
                index: 0x1400,
                subindex: 5,
            },
        ),
        (
            "[[node.tpdo]]\nnumber = 1\nmapping = [\"statusword\",\n\"no_such_thing\"]\n",
            8,
            NetworkFileErrorKind::PdoUnknownParameter {
                name: "no_such_thing".into(),
            },
        ),
        (
            "[[node.tpdo]]\nnumber = 1\nmapping = [\"producer_heartbeat_time\"]\n",
            7,
            NetworkFileErrorKind::PdoNotMappable {
                name: "producer_heartbeat_time".into(),
            },
        ),
        (
            "[[node.tpdo]]\nnumber = 1\nmapping = [\"profile_speed\"]\n",
            7,
            NetworkFileErrorKind::PdoWrongDirection {
                name: "profile_speed".into(),
                wanted: "TPDO",
            },
        ),
        (
            "[[node.rpdo]]\nnumber = 1\n\
             mapping = [\"target_position\", \"profile_speed\", \"target_position\"]\n",
            5,
            NetworkFileErrorKind::PdoTooManyBits {
                pdo: "RPDO 1".into(),
                bits: 96,
            },
        ),
        (
            "[[node.tpdo]]\nnumber = 1\n\
             mapping = [\"statusword\", \"modes_of_operation_display\", \"statusword\"]\n",
            5,
            NetworkFileErrorKind::PdoTooManyEntries {
                pdo: "TPDO 1".into(),
                entries: 3,
                capacity: 2,
                index: 0x1A00,
            },
        ),
    ];
    for (pdos, line, kind) in cases {
        let refused = pdo_refusal(&kinco, pdos);
        assert_eq!((refused.line, refused.kind), (Some(line), kind), "{pdos}");
    }
}

#[test]
fn a_pdo_beyond_the_connection_set_needs_its_cob_id() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/ezwheel-swd");
    let swd = crate::check(path.as_ref())
        .device
        .expect("the SWD description");
    let refused = pdo_refusal(
        &swd,
        "[[node.tpdo]]\nnumber = 5\nmapping = [\"statusword\"]\n",
    );
    assert_eq!(
        (refused.line, refused.kind),
        (
            Some(5),
            NetworkFileErrorKind::PdoNoCobId {
                pdo: "TPDO 5".into()
            }
        )
    );
    let given =
        with_pdos("[[node.tpdo]]\nnumber = 5\ncob_id = 0x2A5\nmapping = [\"statusword\"]\n");
    assert_eq!(check_pdos(&given.nodes[0], &swd).unwrap()[0].cob_id, 0x2A5);
}

#[test]
fn malformed_pdo_tables_are_refused_with_the_line() {
    let head = "format = 1\n[[node]]\nid = 5\ndescription = \"k\"\n[[node.tpdo]]\n";
    for (rest, line) in [
        ("number = 0\nmapping = []\n", 6),
        ("number = 1\ncob_id = 0x800\nmapping = []\n", 7),
        ("number = 1\ntransmission_type = 256\nmapping = []\n", 7),
        ("number = 1\nmapping = []\nsync = 3\n", 8),
        ("number = 1\n", 5),
    ] {
        let refused = refused(&format!("{head}{rest}"));
        assert_eq!(refused.line, Some(line), "{rest}: {refused}");
    }
}

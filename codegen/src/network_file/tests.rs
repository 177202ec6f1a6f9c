use super::*;

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

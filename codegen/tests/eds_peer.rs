//! Every shipped CANopen description (and eight random valid ones) exported as an EDS loads in
//! python canopen 2.4.1 without a warning, with the objects, types, access, defaults and limits of its IR (tests/peers/
//! eds_import_check.py). The peer is required: run tests/peers/setup.sh or set DRIVEGEN_PYTHON.

mod support;

use support::python_eds::python_loads_the_export;
use support::random_description::valid_descriptions;
use support::{canopen_descriptions, device, short_name, Scratch};

#[test]
fn exported_eds_loads_in_python_canopen_with_the_ir_objects() {
    let scratch = Scratch::new("eds-peer");
    let mut failures = Vec::new();
    // The overlay fixture adds a `$NODEID`-relative COB-ID default, resolved by python with
    // `python_eds::NODE_ID`.
    let overlay = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/overlay");
    // And random valid descriptions: every type, limits, defaults, access and variants.
    let random = valid_descriptions(8, &scratch.0);
    for description in canopen_descriptions()
        .into_iter()
        .chain([overlay])
        .chain(random)
    {
        let name = short_name(&description);
        let eds = scratch.0.join(format!("{name}.eds"));
        if let Err(why) = python_loads_the_export(&device(&description), &eds) {
            failures.push(format!("--- {name}: {why}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Issue #27 item 7: a vendor EDS whose `$NODEID+0x180` COB-ID default has absolute limits
/// 0x181..=0x18F (node IDs 1..=15) loads in python canopen on any node ID; drivegen reads it too,
/// with a warning naming the node IDs the limits allow, and its export loads in python canopen
/// with the same objects, default and limits.
#[test]
fn a_vendor_eds_with_limits_narrowing_the_node_id_loads_in_both() {
    let vendor = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/eds/node_id_default_narrowed.eds");
    // python canopen first: the vendor file as it is, on a node ID the limits allow and on one
    // they do not.
    let script = "import sys, canopen\n\
        od = canopen.import_od(sys.argv[1], int(sys.argv[2]))\n\
        v = od[0x1800][1]\n\
        print(v.default, v.min, v.max)\n";
    for (node, default) in [(5u32, 0x185), (16, 0x190)] {
        let output = std::process::Command::new(peer_support::python())
            .args(["-c", script])
            .arg(&vendor)
            .arg(node.to_string())
            .output()
            .expect("python runs; run tests/peers/setup.sh");
        assert!(
            output.status.success(),
            "python canopen refuses the vendor file on node {node}: {}",
            String::from_utf8_lossy(&output.stderr)
        );
        assert_eq!(
            String::from_utf8_lossy(&output.stdout).trim(),
            format!("{default} 385 399"),
            "node {node}"
        );
    }
    let checked = drivegen::check(&vendor);
    let device = checked
        .device
        .as_ref()
        .unwrap_or_else(|| panic!("drivegen refuses it:\n{}", checked.render()));
    let narrowed: Vec<&str> = checked
        .diagnostics
        .iter()
        .filter(|d| d.rule == "defaults_within_range")
        .map(|d| {
            assert_eq!(d.severity, drivegen::Severity::Warning, "{}", d.message);
            d.label.as_str()
        })
        .collect();
    assert_eq!(
        narrowed,
        [
            "the limits allow node IDs 1..=15 only",
            "the limits allow node IDs 16..=32 only"
        ]
    );
    let scratch = Scratch::new("eds-peer-narrowed");
    let eds = scratch.0.join("narrowed.eds");
    python_loads_the_export(device, &eds).unwrap();
}

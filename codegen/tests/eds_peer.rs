//! Every shipped CANopen description (and eight random valid ones) exported as an EDS loads in
//! python canopen 2.4.1 without a warning, with the objects, types, access, defaults and limits of its IR (tests/peers/
//! eds_import_check.py). The peer is required: run tests/peers/setup.sh or set DRIVEGEN_PYTHON.

mod support;

use std::process::Command;

use peer_support::python;
use support::random_description::valid_descriptions;
use support::{canopen_descriptions, device, short_name, workspace_root, Scratch};

/// Node id the relative defaults are resolved with.
const NODE_ID: u8 = 5;

#[test]
fn exported_eds_loads_in_python_canopen_with_the_ir_objects() {
    let scratch = Scratch::new("eds-peer");
    let script = workspace_root().join("tests/peers/eds_import_check.py");
    let mut failures = Vec::new();
    // The overlay fixture adds a `$NODEID`-relative COB-ID default, resolved by python with NODE_ID.
    let overlay = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/overlay");
    // And random valid descriptions: every type, limits, defaults, access and variants.
    let random = valid_descriptions(8, &scratch.0);
    for description in canopen_descriptions()
        .into_iter()
        .chain([overlay])
        .chain(random)
    {
        let device = device(&description);
        let name = short_name(&description);
        let eds = scratch.0.join(format!("{name}.eds"));
        let ir = scratch.0.join(format!("{name}.json"));
        std::fs::write(&eds, drivegen::eds::export(&device)).unwrap();
        std::fs::write(&ir, serde_json::to_string(&device).unwrap()).unwrap();
        let output = Command::new(python())
            .arg(&script)
            .arg(&eds)
            .arg(&ir)
            .arg(NODE_ID.to_string())
            .output()
            .unwrap_or_else(|e| {
                panic!(
                    "cannot start {}: {e}; run tests/peers/setup.sh",
                    python().display()
                )
            });
        let stdout = String::from_utf8_lossy(&output.stdout);
        let stderr = String::from_utf8_lossy(&output.stderr);
        if !output.status.success() {
            failures.push(format!("--- {name}: {stdout}\n{stderr}"));
        } else {
            assert!(stdout.contains("objects compared"), "{name}: {stdout}");
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

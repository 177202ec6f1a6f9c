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

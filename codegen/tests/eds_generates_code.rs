//! Any valid EDS makes a crate: well-formed EDS files with arbitrary names (keywords, digits,
//! punctuation, non-ASCII, clashes), every data type, limits, defaults and `$NODEID` terms are
//! read, and when the device is valid its generated code parses (property test) and a batch of
//! them compiles warning-free (one crate build).

mod support;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use drivegen::diagnostic::Files;
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;
use support::crate_build::assert_descriptions_compile;
use support::Scratch;

/// CiA 301 data type codes drivegen reads (0x000E and 0x0017 are reserved).
const DATA_TYPES: &[u16] = &[
    0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x0A, 0x0B, 0x0C, 0x0D, 0x0F, 0x10, 0x11,
    0x12, 0x13, 0x14, 0x15, 0x16, 0x18, 0x19, 0x1A, 0x1B,
];

/// Names vendors write, and names that are awkward as Rust identifiers.
fn parameter_name() -> impl Strategy<Value = String> {
    prop_oneof![
        "[A-Za-z][A-Za-z0-9 _-]{0,24}",
        "[0-9][A-Za-z0-9 ]{0,8}",
        Just("type".to_owned()),
        Just("Self".to_owned()),
        Just("self".to_owned()),
        Just("crate".to_owned()),
        Just("r#fn".to_owned()),
        Just("_".to_owned()),
        Just("Read".to_owned()),
        Just("Value".to_owned()),
        Just("Highest sub-index supported".to_owned()),
        Just("Drehzahl Ü/min (°C)".to_owned()),
        Just("".to_owned()),
    ]
}

/// A value a type's limits or default may hold: in range for most types, sometimes written in
/// hex or relative to the node id.
fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        (0u8..=127).prop_map(|v| v.to_string()),
        (0u8..=127).prop_map(|v| format!("0x{v:X}")),
        (-5i8..=0).prop_map(|v| v.to_string()),
        (0u8..=100).prop_map(|v| format!("{}.5", v)),
        (0u8..=15).prop_map(|v| format!("$NODEID+0x{:X}", 0x180 + u16::from(v))),
    ]
}

/// The keys of one variable: type, access, PDO mapping, and optional limits and default.
fn variable_keys() -> impl Strategy<Value = String> {
    (
        proptest::sample::select(DATA_TYPES),
        proptest::sample::select(&["ro", "wo", "rw", "rwr", "rww", "const"][..]),
        any::<bool>(),
        proptest::option::of(value()),
        proptest::option::of(value()),
        proptest::option::of(value()),
    )
        .prop_map(|(code, access, pdo, low, high, default)| {
            let mut keys = format!(
                "DataType=0x{code:04X}\nAccessType={access}\nPDOMapping={}\n",
                u8::from(pdo)
            );
            let keys_of = [
                ("LowLimit", low),
                ("HighLimit", high),
                ("DefaultValue", default),
            ];
            for (key, value) in keys_of {
                if let Some(value) = value {
                    let _ = writeln!(keys, "{key}={value}");
                }
            }
            keys
        })
}

/// One object: a VAR, or a RECORD / ARRAY of one to four sub-indices.
fn object(index: u16) -> impl Strategy<Value = String> {
    let var = (parameter_name(), variable_keys()).prop_map(move |(name, keys)| {
        format!("[{index:04X}]\nParameterName={name}\nObjectType=0x7\n{keys}\n")
    });
    let members = proptest::collection::vec((parameter_name(), variable_keys()), 1..=4);
    let record = (parameter_name(), prop_oneof![Just(8), Just(9)], members).prop_map(
        move |(name, code, members)| {
            let mut text = format!(
                "[{index:04X}]\nParameterName={name}\nObjectType=0x{code}\nSubNumber={}\n\n",
                members.len() + 1
            );
            let count = members.len();
            let _ = write!(text, "[{index:04X}sub0]\nParameterName=Number of entries\nDataType=0x0005\nAccessType=ro\nDefaultValue={count}\n\n");
            for (sub, (name, keys)) in members.into_iter().enumerate() {
                let _ = write!(text, "[{index:04X}sub{:X}]\nParameterName={name}\n{keys}\n", sub + 1);
            }
            text
        },
    );
    prop_oneof![var, record]
}

/// A whole EDS of one to eight objects at ascending indices.
fn eds() -> impl Strategy<Value = String> {
    proptest::collection::btree_set(0x2000u16..0x2100, 1..=8).prop_flat_map(|indices| {
        let objects: Vec<_> = indices.into_iter().map(object).collect();
        objects.prop_map(|objects| {
            let head = "[FileInfo]\nFileName=random.eds\nEDSVersion=4.0\n\n[DeviceInfo]\nVendorName=ACME\nProductName=Random\n\n";
            head.to_owned() + &objects.concat()
        })
    })
}

/// The device of an EDS text, when it is valid.
fn valid_device(text: &str) -> Option<drivegen::ir::Device> {
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let model = drivegen::eds::read_bytes(
        Path::new("random.eds"),
        text.as_bytes(),
        &mut files,
        &mut diagnostics,
    );
    let mut device = drivegen::eds::empty_device("Random", &model);
    device.parameters =
        drivegen::eds::typed_parameters(model.entries, &model.cited, &mut diagnostics);
    diagnostics.extend(drivegen::validate::validate(&device));
    let valid = !diagnostics
        .iter()
        .any(|d| d.severity == drivegen::Severity::Error);
    valid.then_some(device)
}

proptest! {
    #[test]
    fn a_valid_eds_generates_code_that_parses(text in eds()) {
        if let Some(device) = valid_device(&text) {
            // `generate` parses its own output and panics if it is not Rust.
            let code = drivegen::emit::rust::generate(&device, "random");
            prop_assert!(code.contains("pub mod params"), "{}", code);
        }
    }
}

/// Generated EDS files that make valid devices, the same on every run.
fn valid_samples(count: usize) -> Vec<String> {
    let mut runner = TestRunner::deterministic();
    let strategy = eds();
    let mut samples = Vec::new();
    while samples.len() < count {
        let text = strategy.new_tree(&mut runner).unwrap().current();
        if valid_device(&text).is_some() {
            samples.push(text);
        }
    }
    samples
}

#[test]
fn code_generated_from_random_valid_eds_files_compiles_without_warnings() {
    let scratch = Scratch::new("eds-generates-code");
    let paths: Vec<PathBuf> = valid_samples(24)
        .iter()
        .enumerate()
        .map(|(i, text)| {
            let path = scratch.0.join(format!("random_{i}.eds"));
            std::fs::write(&path, text).unwrap();
            path
        })
        .collect();
    // The EDS files stay for reading after a failure with DRIVEGEN_KEEP_SCRATCH set.
    assert_descriptions_compile("random_eds", &paths);
}

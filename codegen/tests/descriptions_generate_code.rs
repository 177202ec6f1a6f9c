//! Any valid TOML description makes a crate: random descriptions combining every type, units,
//! fixed scales, ranges, defaults, allowed values, enums, flags, variants, commands, effects and
//! Modbus and CANopen addresses are checked, and when valid their generated code parses (property
//! test) and a batch of them compiles warning-free (one crate build).

mod support;

use proptest::prelude::*;
use support::crate_build::assert_descriptions_compile;
use support::random_description::{description, valid_descriptions};
use support::Scratch;

/// The device of a description text written to `scratch`, when it is valid.
fn check(text: &str, path: &std::path::Path) -> Option<drivegen::ir::Device> {
    std::fs::write(path, text).unwrap();
    drivegen::check(path).device
}

proptest! {
    #[test]
    fn a_valid_description_generates_code_that_parses(text in description()) {
        let scratch = Scratch::new("random-description");
        if let Some(device) = check(&text, &scratch.0.join("device.toml")) {
            // `generate` parses its own output and panics if it is not Rust.
            let code = drivegen::emit::rust::generate(&device, "random");
            prop_assert!(code.contains("pub mod params"), "{}", code);
        }
    }
}

#[test]
fn code_generated_from_random_valid_descriptions_compiles_without_warnings() {
    let scratch = Scratch::new("descriptions-generate-code");
    // The descriptions stay for reading after a failure with DRIVEGEN_KEEP_SCRATCH set.
    assert_descriptions_compile("random_toml", &valid_descriptions(24, &scratch.0));
}

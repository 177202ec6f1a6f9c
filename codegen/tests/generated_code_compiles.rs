//! The generated code of every shipped description compiles warning-free and `no_std`, with docs
//! on every item — not only the Lafert crate that `drives/` builds. Variants, run-time scales,
//! records and CANopen-only parameters are exercised here by the Kinco, Lenze and ez-Wheel files.

mod support;

use support::crate_build::{build_and_doctest, generated};
use support::{shipped_descriptions, short_name};

#[test]
fn every_shipped_description_compiles_without_warnings() {
    let mut lib = String::from(
        "//! Every shipped description.\n#![no_std]\n#![deny(warnings, missing_docs)]\n#[cfg(feature = \"std\")]\nextern crate std;\n",
    );
    for path in shipped_descriptions() {
        let module = short_name(&path).replace('-', "_");
        lib += &format!(
            "/// Generated from {module}.\npub mod {module} {{\n{}\n}}\n",
            generated(&path)
        );
    }
    let built = build_and_doctest("shipped", &lib);
    assert!(
        built.success,
        "generated code does not build:\n{}",
        built.stderr
    );
}

//! The generated code of every shipped description compiles warning-free and `no_std`, with docs
//! on every item — not only the Lafert crate that `drives/` builds. Variants, run-time scales,
//! records and CANopen-only parameters are exercised here by the Kinco, Lenze and ez-Wheel files;
//! names derived from vendor text by the EDS corpus and the EDS + overlay fixture.

mod support;

use std::path::{Path, PathBuf};

use support::crate_build::assert_descriptions_compile;
use support::shipped_descriptions;

#[test]
fn every_shipped_description_compiles_without_warnings() {
    assert_descriptions_compile("shipped", &shipped_descriptions());
}

/// Every EDS of the corpus that is a valid device on its own (keywords, digits, clashing and
/// non-ASCII names, wide types, `$NODEID` defaults...), and the EDS + overlay fixture.
#[test]
fn code_generated_from_eds_files_compiles_without_warnings() {
    let mut descriptions: Vec<PathBuf> = std::fs::read_dir("tests/eds")
        .expect("tests/eds exists")
        .map(|e| e.unwrap().path())
        .filter(|p| drivegen::eds::is_eds_path(p) && drivegen::check(p).device.is_some())
        .collect();
    descriptions.sort();
    assert!(
        descriptions.len() >= 20,
        "only {} valid EDS files",
        descriptions.len()
    );
    descriptions.push(Path::new("tests/fixtures/overlay").to_path_buf());
    assert_descriptions_compile("from_eds", &descriptions);
}

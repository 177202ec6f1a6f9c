//! The EDS corpus end to end, as a user points `drivegen eds import` at a vendor file: every
//! `tests/eds/*.eds` / `*.dcf` imports with the findings of the EDS alone, its overlay skeleton
//! checks as written (but for the two files meant to fail), the crates generated
//! from all of them compile (one crate build), and the EDS exported from each loads in python
//! canopen 2.4.1 with the objects of the IR (tests/peers/eds_import_check.py). The peer is
//! required: run tests/peers/setup.sh or set DRIVEGEN_PYTHON.

mod support;

use std::path::{Path, PathBuf};

use drivegen::Severity;
use support::crate_build::assert_descriptions_compile;
use support::{python_eds, Scratch};

/// Every EDS / DCF of the corpus.
fn corpus() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir("tests/eds")
        .expect("tests/eds exists")
        .map(|e| e.unwrap().path())
        .filter(|p| drivegen::eds::is_eds_path(p))
        .collect();
    files.sort();
    files
}

/// The findings of a check, without their file paths (the import checks a copy of the EDS).
fn findings(checked: &drivegen::Checked) -> Vec<(Severity, &'static str, String)> {
    let all = checked.diagnostics.iter();
    all.map(|d| (d.severity, d.rule, d.message.clone()))
        .collect()
}

/// Copies `eds` into `scratch`, imports it there and saves the overlay beside it. The overlay's
/// path when it checks (`None` when the EDS alone does not check either, with the same errors),
/// or why the import is wrong.
fn import(eds: &Path, scratch: &Path) -> Result<Option<PathBuf>, String> {
    let copy = scratch.join(eds.file_name().unwrap());
    std::fs::copy(eds, &copy).unwrap();
    let overlay = drivegen::eds::default_overlay_path(&copy);
    let imported = drivegen::eds::import_overlay(&copy, &overlay).map_err(|e| e.to_string())?;
    std::fs::write(&overlay, &imported.overlay).unwrap();
    let alone = drivegen::check(eds);
    // The import reports exactly what checking the EDS alone reports (each once).
    match (
        imported.checks(),
        findings(&imported.checked) == findings(&alone),
    ) {
        (true, true) => Ok(Some(overlay)),
        (false, true) => Ok(None),
        _ => Err(format!(
            "the skeleton's check:\n{}\ndiffers from the EDS's:\n{}",
            imported.checked.render(),
            alone.render()
        )),
    }
}

/// Exports the device of `overlay` and has python canopen compare it with the IR.
fn python_loads_the_export(overlay: &Path) -> Result<(), String> {
    let eds = overlay.with_extension("exported.eds");
    python_eds::python_loads_the_export(&support::device(overlay), &eds)
}

#[test]
fn every_corpus_file_imports_checks_compiles_and_exports_for_python_canopen() {
    let scratch = Scratch::new("eds-corpus-round-trip");
    let mut failures = Vec::new();
    let mut overlays = Vec::new();
    let mut refused = Vec::new();
    let files = corpus();
    assert!(files.len() >= 40, "the corpus holds {} files", files.len());
    for eds in &files {
        let result = import(eds, &scratch.0).and_then(|overlay| {
            overlay.as_deref().map_or(Ok(()), python_loads_the_export)?;
            Ok(overlay)
        });
        match result {
            Ok(Some(overlay)) => overlays.push(overlay),
            Ok(None) => refused.push(eds.file_name().unwrap().to_string_lossy().into_owned()),
            Err(why) => failures.push(format!("--- {}: {why}", eds.display())),
        }
    }
    // Only the defaults their own limits refuse (on every node ID, for a node-relative one) are
    // meant not to check.
    assert_eq!(
        refused,
        [
            "default_outside_limits.eds",
            "node_id_default_outside_limits.eds"
        ],
        "corpus files that do not check"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_descriptions_compile("eds_corpus_round_trip", &overlays);
}

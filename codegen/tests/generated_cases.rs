//! Generated-code cases, one per description-format feature (as device-driver's `tests/ui/cases`):
//! each `tests/cases/<feature>/description.toml` is checked, its rendered diagnostics (warnings;
//! empty when none) are compared with `diagnostics.txt` and its generated Rust with `expected.rs`,
//! and all cases' code is compiled together in one scratch crate, one module per case. An emitter
//! change is reviewed on these small files. Re-bless these and the whole-drive snapshots with one
//! command, `DRIVEGEN_BLESS=1 INSTA_UPDATE=always cargo test -p drivegen --test generated_cases
//! --test generated_snapshots`, and review the diff.

mod support;

use std::path::{Path, PathBuf};

use support::crate_build::{build_and_doctest, no_std_lib};

/// Every case folder, sorted.
fn cases() -> Vec<PathBuf> {
    let mut cases: Vec<PathBuf> = std::fs::read_dir("tests/cases")
        .expect("tests/cases exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("description.toml").is_file())
        .collect();
    cases.sort();
    cases
}

fn name(case: &Path) -> String {
    case.file_name().unwrap().to_string_lossy().into_owned()
}

/// A case's diagnostics and generated code; panics when the description is invalid.
fn outputs(case: &Path) -> (String, String) {
    let checked = drivegen::check(&case.join("description.toml"));
    let diagnostics = checked.render();
    let device = checked
        .device
        .unwrap_or_else(|| panic!("{}: invalid description\n{diagnostics}", case.display()));
    let code = drivegen::emit::rust::generate(&device, &format!("{}.toml", name(case)));
    (diagnostics, code)
}

#[test]
fn every_case_generates_its_expected_code_and_diagnostics() {
    let bless = std::env::var_os("DRIVEGEN_BLESS").is_some();
    let cases = cases();
    assert!(cases.len() >= 10, "only {} cases", cases.len());
    let mut failures = Vec::new();
    for case in cases {
        let (diagnostics, code) = outputs(&case);
        for (file, actual) in [("diagnostics.txt", diagnostics), ("expected.rs", code)] {
            let path = case.join(file);
            if bless {
                std::fs::write(&path, &actual).unwrap();
                continue;
            }
            let expected = std::fs::read_to_string(&path).unwrap_or_default();
            if expected != actual {
                failures.push(format!(
                    "--- {}\n{}",
                    path.display(),
                    diff(&expected, &actual)
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{}\n(re-bless with DRIVEGEN_BLESS=1 and review the diff)",
        failures.join("\n")
    );
}

/// The first lines where `expected` and `actual` differ, enough to see what changed.
fn diff(expected: &str, actual: &str) -> String {
    let (e, a): (Vec<&str>, Vec<&str>) = (expected.lines().collect(), actual.lines().collect());
    let first = e.iter().zip(&a).take_while(|(x, y)| x == y).count();
    let show = |lines: &[&str]| {
        let shown: Vec<&str> = lines.iter().skip(first).take(8).copied().collect();
        shown.join("\n")
    };
    format!(
        "first difference at line {}\nexpected:\n{}\nactual:\n{}",
        first + 1,
        show(&e),
        show(&a)
    )
}

#[test]
fn the_code_of_every_case_compiles_without_warnings() {
    let modules: String = cases()
        .iter()
        .map(|case| {
            let (_, code) = outputs(case);
            format!("/// Case {0}.\npub mod {0} {{\n{code}\n}}\n", name(case))
        })
        .collect();
    let built = build_and_doctest("cases", &no_std_lib(&modules));
    assert!(
        built.success,
        "generated code does not build:\n{}",
        built.stderr
    );
}

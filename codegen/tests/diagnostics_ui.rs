//! UI tests of the diagnostics: every `tests/ui/*.toml` is checked and its rendered diagnostics are
//! compared with the `.stderr` file beside it. Re-bless with `DRIVEGEN_BLESS=1 cargo test -p
//! drivegen --test diagnostics_ui` and review the diff.

use std::path::{Path, PathBuf};

fn cases() -> Vec<PathBuf> {
    let mut cases: Vec<PathBuf> = std::fs::read_dir("tests/ui")
        .expect("tests/ui exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    cases.sort();
    cases
}

fn expected_path(case: &Path) -> PathBuf {
    case.with_extension("stderr")
}

#[test]
fn every_bad_description_has_its_expected_diagnostics() {
    let bless = std::env::var_os("DRIVEGEN_BLESS").is_some();
    let mut failures = Vec::new();
    for case in cases() {
        let checked = drivegen::check(&case);
        let actual = checked.render();
        assert!(
            checked.device.is_none(),
            "{}: a UI case must be invalid",
            case.display()
        );
        let expected_file = expected_path(&case);
        if bless {
            std::fs::write(&expected_file, &actual).unwrap();
            continue;
        }
        let expected = std::fs::read_to_string(&expected_file).unwrap_or_default();
        if expected != actual {
            failures.push(format!(
                "--- {}\nexpected:\n{expected}\nactual:\n{actual}",
                case.display()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{}\n(re-bless with DRIVEGEN_BLESS=1)",
        failures.join("\n")
    );
}

#[test]
fn every_rule_has_a_ui_case() {
    let names: Vec<String> = cases()
        .iter()
        .map(|c| std::fs::read_to_string(expected_path(c)).unwrap_or_default())
        .collect();
    for (rule, _) in drivegen::validate::PASSES {
        assert!(
            names.iter().any(|text| text.contains(&format!("[{rule}]"))),
            "no UI case shows rule `{rule}`"
        );
    }
}

//! The EDS corpus: every `tests/eds/*.eds` / `*.dcf` is checked; its rendered diagnostics are
//! compared with the `.stderr` file beside it and, when it is valid, its IR with the `.json` file.
//! Re-bless with `DRIVEGEN_BLESS=1 cargo test -p drivegen --test eds_corpus` and review the diff.

use std::path::{Path, PathBuf};

fn cases() -> Vec<PathBuf> {
    let mut cases: Vec<PathBuf> = std::fs::read_dir("tests/eds")
        .expect("tests/eds exists")
        .map(|e| e.unwrap().path())
        .filter(|p| drivegen::eds::is_eds_path(p))
        .collect();
    cases.sort();
    cases
}

/// Compares `actual` with the file at `path`, or writes it when blessing.
fn compare(path: &Path, actual: &str, failures: &mut Vec<String>) {
    if std::env::var_os("DRIVEGEN_BLESS").is_some() {
        if actual.is_empty() {
            let _ = std::fs::remove_file(path);
        } else {
            std::fs::write(path, actual).unwrap();
        }
        return;
    }
    let expected = std::fs::read_to_string(path).unwrap_or_default();
    if expected != actual {
        failures.push(format!(
            "--- {}\nexpected:\n{expected}\nactual:\n{actual}",
            path.display()
        ));
    }
}

#[test]
fn every_eds_has_its_expected_ir_or_diagnostics() {
    let mut failures = Vec::new();
    let all = cases();
    assert!(all.len() >= 25, "the corpus holds {} files", all.len());
    for case in all {
        let checked = drivegen::check(&case);
        compare(
            &case.with_extension("stderr"),
            &checked.render(),
            &mut failures,
        );
        let json = checked
            .device
            .as_ref()
            .map(|d| serde_json::to_string_pretty(d).unwrap() + "\n")
            .unwrap_or_default();
        compare(&case.with_extension("json"), &json, &mut failures);
    }
    assert!(
        failures.is_empty(),
        "{}\n(re-bless with DRIVEGEN_BLESS=1)",
        failures.join("\n")
    );
}

#[test]
fn hostile_eds_text_cannot_inject_code() {
    let checked = drivegen::check(Path::new("tests/eds/hostile_names.eds"));
    let device = checked
        .device
        .expect("names are sanitized, so the EDS is valid");
    let code = drivegen::emit::rust::generate(&device, "hostile");
    assert!(
        code.contains("no_std"),
        "the description is kept as documentation:\n{code}"
    );
    for line in code
        .lines()
        .filter(|l| l.contains("process::exit") || l.contains("no_std"))
    {
        let trimmed = line.trim_start();
        assert!(
            trimmed.starts_with("///")
                || trimmed.starts_with("//!")
                || trimmed.starts_with("#[doc"),
            "description text escaped into code: {line}"
        );
    }
    let exported = drivegen::eds::export(&device);
    assert!(
        exported.lines().all(|l| !l.starts_with("fn main")),
        "{exported}"
    );
}

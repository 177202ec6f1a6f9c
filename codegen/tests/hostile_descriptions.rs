//! A description full of quotes, comment terminators, braces, keywords, code and doc-test fences
//! must generate code that compiles, defines nothing but what the description declares, and has no
//! doctest to run.

use std::path::Path;
use std::process::Command;

fn generate(path: &str) -> String {
    let checked = drivegen::check(Path::new(path));
    let device = checked
        .device
        .as_ref()
        .unwrap_or_else(|| panic!("{}", checked.render()));
    drivegen::emit::rust::generate(device, "hostile.toml")
}

#[test]
fn hostile_names_and_docs_cannot_inject_items() {
    let source = generate("tests/fixtures/hostile.toml");
    let file = syn::parse_file(&source).expect("generated code parses");
    let fn_names: Vec<String> = file
        .items
        .iter()
        .filter_map(|item| match item {
            syn::Item::Fn(f) => Some(f.sig.ident.to_string()),
            _ => None,
        })
        .collect();
    assert!(
        fn_names.is_empty(),
        "no free functions are generated: {fn_names:?}"
    );
    assert!(!source.contains("fn injected"), "a doc or name became code");
    assert!(
        !source.contains("\n```"),
        "a doc line opens a code block (doctest)"
    );
    assert!(
        !source.contains("///     "),
        "an indented doc line would be a doctest"
    );
}

/// Builds the generated code in a scratch crate with `#![deny(warnings)]` and runs its doctests.
#[test]
fn hostile_description_compiles_without_warnings_and_without_doctests() {
    let source = generate("tests/fixtures/hostile.toml");
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
    let dir = workspace.join("target/fixtures/hostile");
    std::fs::create_dir_all(dir.join("src")).unwrap();
    let manifest = format!(
        "[package]\nname = \"hostile\"\nversion = \"0.0.0\"\nedition = \"2021\"\n[dependencies]\ndrivebus = {{ path = {:?} }}\n[workspace]\n",
        workspace.join("transport")
    );
    std::fs::write(dir.join("Cargo.toml"), manifest).unwrap();
    let lib =
        format!("//! Hostile fixture.\n#![no_std]\n#![deny(warnings, missing_docs)]\n{source}");
    std::fs::write(dir.join("src/lib.rs"), lib).unwrap();
    let output = Command::new(env!("CARGO"))
        .args(["test", "--offline", "--doc", "--manifest-path"])
        .arg(dir.join("Cargo.toml"))
        .env("CARGO_TARGET_DIR", workspace.join("target/fixtures/target"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "generated code does not build:\n{stderr}"
    );
    assert!(
        stdout.contains("running 0 tests"),
        "a description doc became a doctest:\n{stdout}"
    );
}

//! Snapshot tests (insta) of the generated Rust of every shipped description, so every change to
//! the emitter or a description shows up as a reviewable diff. Accept changes with
//! `cargo insta review` or `INSTA_UPDATE=always cargo test -p drivegen --test generated_snapshots`.

use std::path::{Path, PathBuf};

/// Every shipped description: each family folder and each profile.
fn shipped() -> Vec<(String, PathBuf)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../descriptions");
    let mut found = Vec::new();
    for entry in std::fs::read_dir(&root).expect("descriptions/ exists") {
        let path = entry.unwrap().path();
        if path.join("device.toml").is_file() {
            found.push((
                path.file_name().unwrap().to_string_lossy().into_owned(),
                path,
            ));
        }
    }
    for entry in std::fs::read_dir(root.join("profiles"))
        .into_iter()
        .flatten()
    {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            found.push((
                format!("profile-{}", path.file_stem().unwrap().to_string_lossy()),
                path,
            ));
        }
    }
    found.sort();
    found
}

#[test]
fn every_shipped_description_is_valid_and_its_code_is_snapshotted() {
    let shipped = shipped();
    assert!(shipped.iter().any(|(name, _)| name == "lafert-smartris"));
    for (name, path) in shipped {
        let checked = drivegen::check(&path);
        let device = checked
            .device
            .as_ref()
            .unwrap_or_else(|| panic!("{name}:\n{}", checked.render()));
        let code = drivegen::emit::rust::generate(device, &name);
        insta::assert_snapshot!(name, code);
    }
}

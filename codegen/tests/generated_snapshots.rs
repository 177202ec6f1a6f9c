//! One whole-drive snapshot (insta) per drive family, so a change to the emitter or a description
//! shows up in context. Each format feature has its own small case in `tests/cases`
//! (`generated_cases.rs`), which is where an emitter change is reviewed; the profiles are covered
//! there. Accept changes with `cargo insta review`, or re-bless both with `DRIVEGEN_BLESS=1
//! INSTA_UPDATE=always cargo test -p drivegen --test generated_cases --test generated_snapshots`.

use std::path::{Path, PathBuf};

/// Every drive family's description folder.
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
    found.sort();
    found
}

#[test]
fn every_drive_family_is_valid_and_its_code_is_snapshotted() {
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

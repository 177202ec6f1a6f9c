//! `drivegen new`: the crate it writes (skeleton or EDS overlay) has a valid description, and bad
//! input — a non-empty folder, an invalid crate name, an unreadable EDS — is refused with a clear
//! message and nothing written. `scripts/new-drive.sh` builds the crates it writes with cargo.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// An empty folder of its own for each test.
fn scratch(label: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("drivegen-new-{label}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn drivegen() -> Command {
    Command::new(env!("CARGO_BIN_EXE_drivegen"))
}

fn new_crate(target: &Path, extra: &[&str]) -> Output {
    drivegen()
        .arg("new")
        .arg(target)
        .args(extra)
        .output()
        .unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Every file under `dir`, relative, sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut found = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(folder) = pending.pop() {
        for entry in std::fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else {
                found.push(path.strip_prefix(dir).unwrap().display().to_string());
            }
        }
    }
    found.sort();
    found
}

fn check_passes(description: &Path) -> String {
    let check = drivegen().arg("check").arg(description).output().unwrap();
    assert!(check.status.success(), "{}", stderr(&check));
    String::from_utf8_lossy(&check.stdout).into_owned()
}

#[test]
fn the_skeleton_crate_has_every_file_and_a_valid_description() {
    let dir = scratch("skeleton");
    let target = dir.join("acme-fd3");
    let created = new_crate(&target, &[]);
    assert!(created.status.success(), "{}", stderr(&created));
    assert_eq!(
        files(&target),
        [
            ".gitignore",
            "Cargo.toml",
            "README.md",
            "build.rs",
            "descriptions/acme-fd3/device.toml",
            "src/lib.rs",
        ]
    );
    let manifest = std::fs::read_to_string(target.join("Cargo.toml")).unwrap();
    assert!(manifest.contains("name = \"acme-fd3\""), "{manifest}");
    // Built from this checkout, the binary points the crate at it.
    let transport = root().join("drivebus").canonicalize().unwrap();
    assert!(
        manifest.contains(&format!("path = \"{}\"", transport.display())),
        "{manifest}"
    );
    let build = std::fs::read_to_string(target.join("build.rs")).unwrap();
    assert!(
        build.contains("Builder::new(\"descriptions/acme-fd3\")"),
        "{build}"
    );
    let summary = check_passes(&target.join("descriptions/acme-fd3"));
    assert!(summary.starts_with("Acme Fd3: 2 parameters"), "{summary}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn from_an_eds_the_crate_holds_the_eds_and_its_overlay() {
    let dir = scratch("eds");
    let eds = root().join("codegen/tests/eds/access_types.eds");
    let target = dir.join("eds-drive");
    let created = new_crate(&target, &["--from", eds.to_str().unwrap()]);
    assert!(created.status.success(), "{}", stderr(&created));
    let folder = target.join("descriptions/eds-drive");
    assert_eq!(
        std::fs::read(folder.join("access_types.eds")).unwrap(),
        std::fs::read(&eds).unwrap()
    );
    let overlay = std::fs::read_to_string(folder.join("device.toml")).unwrap();
    assert!(overlay.contains("eds = \"access_types.eds\""), "{overlay}");
    check_passes(&folder);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn an_existing_non_empty_folder_is_left_as_it_was() {
    let dir = scratch("nonempty");
    let target = dir.join("my-drive");
    std::fs::create_dir(&target).unwrap();
    std::fs::write(target.join("notes.txt"), "mine").unwrap();
    let refused = new_crate(&target, &[]);
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("already exists and is not an empty folder"),
        "{}",
        stderr(&refused)
    );
    assert_eq!(files(&dir), ["my-drive/notes.txt"]);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn an_invalid_crate_name_is_refused_before_anything_is_written() {
    let dir = scratch("names");
    for (name, why) in [
        ("3phase", "starts with `3`"),
        ("my drive", "` ` is not allowed"),
        ("fn", "Rust keyword"),
    ] {
        let refused = new_crate(&dir.join(name), &[]);
        assert!(!refused.status.success(), "{name}");
        let message = stderr(&refused);
        assert!(
            message.contains(&format!("`{name}` cannot be a crate name")) && message.contains(why),
            "{name}: {message}"
        );
    }
    let by_flag = new_crate(&dir.join("ok-folder"), &["--name", "bad.name"]);
    assert!(
        stderr(&by_flag).contains("`.` is not allowed"),
        "{}",
        stderr(&by_flag)
    );
    assert!(files(&dir).is_empty(), "{:?}", files(&dir));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn an_eds_that_cannot_be_imported_writes_nothing() {
    let dir = scratch("bad-eds");
    // The default of this EDS's object lies outside its own limits: only an overlay could fix it.
    let eds = root().join("codegen/tests/eds/default_outside_limits.eds");
    let refused = new_crate(
        &dir.join("vendor-drive"),
        &["--from", eds.to_str().unwrap()],
    );
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("is outside its range 10..=20")
            && stderr(&refused).contains("no crate was made"),
        "{}",
        stderr(&refused)
    );
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    std::fs::remove_dir_all(dir).unwrap();
}

//! Shared helpers of the integration tests.
#![allow(dead_code)] // Each test file uses part of this module.

pub mod crate_build;
pub mod python_eds;
pub mod random_description;

use std::path::{Path, PathBuf};

/// The workspace root.
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("codegen/ lives in the workspace")
        .to_path_buf()
}

/// Every shipped description with CANopen addresses.
pub fn canopen_descriptions() -> Vec<PathBuf> {
    let d = workspace_root().join("descriptions");
    vec![
        d.join("lafert-smartris"),
        d.join("kinco-fd"),
        d.join("ezwheel-swd"),
        d.join("profiles").join("cia301.toml"),
        d.join("profiles").join("cia402.toml"),
    ]
}

/// Every shipped description: each drive family and each profile.
pub fn shipped_descriptions() -> Vec<PathBuf> {
    let d = workspace_root().join("descriptions");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("device.toml").is_file())
        .collect();
    paths.sort();
    paths.push(d.join("profiles").join("cia301.toml"));
    paths.push(d.join("profiles").join("cia402.toml"));
    paths
}

/// The valid device model of a description; panics with its diagnostics otherwise.
pub fn device(path: &Path) -> drivegen::ir::Device {
    let checked = drivegen::check(path);
    match checked.device {
        Some(device) => device,
        None => panic!("{} is invalid:\n{}", path.display(), checked.render()),
    }
}

/// A fresh scratch directory for one test, removed when dropped unless `DRIVEGEN_KEEP_SCRATCH` is
/// set (to read the exported files after a failure).
pub struct Scratch(pub PathBuf);

impl Scratch {
    pub fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("drivegen-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temp dir is writable");
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if std::env::var_os("DRIVEGEN_KEEP_SCRATCH").is_some() {
            eprintln!("scratch files kept in {}", self.0.display());
            return;
        }
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A short name of a description path (`lafert-smartris`, `cia301`, `overlay`).
pub fn short_name(path: &Path) -> String {
    path.file_stem().unwrap().to_string_lossy().into_owned()
}

//! A per-process scratch folder for the loaders that read files (TOML descriptions, EDS overlays).
//!
//! The folder is `$TMPDIR/drivegen-fuzz-<pid>` and stays after the process ends (a crash must not
//! lose the files it read); `fuzz/smoke` points `TMPDIR` into `fuzz/target` and removes it.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The scratch folder, made once per fuzzing process.
fn folder() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("drivegen-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a scratch folder");
        dir
    })
}

/// Writes `bytes` to `name` in the scratch folder (replacing any earlier content) and returns
/// its path.
pub fn write(name: &str, bytes: &[u8]) -> PathBuf {
    let path = folder().join(name);
    std::fs::write(&path, bytes).expect("scratch file written");
    path
}

//! Building generated code in a scratch crate, the way a drive crate would.

use std::path::Path;
use std::process::Command;

use super::workspace_root;

/// What `cargo test --doc` said about a scratch crate.
pub struct Built {
    /// Whether the crate built and its doctests ran.
    pub success: bool,
    pub stdout: String,
    pub stderr: String,
}

/// Writes `lib_rs` as the `src/lib.rs` of a scratch crate `name` depending on `drivebus`, with a
/// default `std` feature as drive crates have, builds it and runs its doctests. All scratch crates share one target directory, so `drivebus` is built
/// once.
pub fn build_and_doctest(name: &str, lib_rs: &str) -> Built {
    let workspace = workspace_root();
    let dir = workspace.join("target/fixtures").join(name);
    std::fs::create_dir_all(dir.join("src")).unwrap();
    let manifest = format!(
        "[package]\nname = \"{name}\"\nversion = \"0.0.0\"\nedition = \"2021\"\n[dependencies]\ndrivebus = {{ path = {:?} }}\n[features]\ndefault = [\"std\"]\nstd = [\"drivebus/std\"]\n[workspace]\n",
        workspace.join("transport")
    );
    std::fs::write(dir.join("Cargo.toml"), manifest).unwrap();
    std::fs::write(dir.join("src/lib.rs"), lib_rs).unwrap();
    let output = Command::new(env!("CARGO"))
        .args(["test", "--offline", "--doc", "--manifest-path"])
        .arg(dir.join("Cargo.toml"))
        .env("CARGO_TARGET_DIR", workspace.join("target/fixtures/target"))
        .output()
        .unwrap();
    Built {
        success: output.status.success(),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

/// The generated Rust source of a description.
pub fn generated(path: &Path) -> String {
    drivegen::emit::rust::generate(&super::device(path), &super::short_name(path))
}

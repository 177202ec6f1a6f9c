//! Building generated code in a scratch crate, the way a drive crate would.

use std::path::{Path, PathBuf};
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
/// default `std` feature as drive crates have, builds it and runs its doctests. All scratch crates
/// share one target directory, so `drivebus` is built once.
pub fn build_and_doctest(name: &str, lib_rs: &str) -> Built {
    let dir = scratch_crate(name, lib_rs, "");
    cargo_test(&dir, &["--doc"])
}

/// Like [`build_and_doctest`], with `test_rs` as an integration test that may use the simulator
/// (`drivesim`) and the test doubles (`drivebus::testing`), and runs every test.
pub fn build_and_test(name: &str, lib_rs: &str, test_rs: &str) -> Built {
    let dev_dependencies = format!(
        "drivesim = {{ path = {:?} }}\ndrivebus = {{ path = {:?}, features = [\"testing\"] }}\n",
        workspace_root().join("drivesim"),
        workspace_root().join("drivebus")
    );
    let dir = scratch_crate(name, lib_rs, &dev_dependencies);
    std::fs::create_dir_all(dir.join("tests")).unwrap();
    std::fs::write(dir.join("tests/generated.rs"), test_rs).unwrap();
    cargo_test(&dir, &[])
}

/// The folder of scratch crate `name`, written with `lib_rs` and `dev_dependencies` (TOML lines).
fn scratch_crate(name: &str, lib_rs: &str, dev_dependencies: &str) -> PathBuf {
    let workspace = workspace_root();
    let dir = workspace.join("target/fixtures").join(name);
    std::fs::create_dir_all(dir.join("src")).unwrap();
    let manifest = format!(
        "[package]\nname = \"{name}\"\nversion = \"0.0.0\"\nedition = \"2021\"\n[dependencies]\ndrivebus = {{ path = {:?}, features = [\"srdo\"] }}\n[dev-dependencies]\n{dev_dependencies}[features]\ndefault = [\"std\"]\nstd = [\"drivebus/std\"]\n[workspace]\n",
        workspace.join("drivebus")
    );
    std::fs::write(dir.join("Cargo.toml"), manifest).unwrap();
    std::fs::write(dir.join("src/lib.rs"), lib_rs).unwrap();
    dir
}

/// `cargo test --offline <args>` in the scratch crate at `dir`.
fn cargo_test(dir: &Path, args: &[&str]) -> Built {
    let output = Command::new(env!("CARGO"))
        .args(["test", "--offline"])
        .args(args)
        .arg("--manifest-path")
        .arg(dir.join("Cargo.toml"))
        .env(
            "CARGO_TARGET_DIR",
            workspace_root().join("target/fixtures/target"),
        )
        // Without debug info, as scripts/package.sh builds: the scratch crates and their
        // dependencies only need to build and run, and full debug info (a scratch crate has no
        // workspace profile) made them slower to compile and link. Panics keep file and line.
        .env("CARGO_PROFILE_DEV_DEBUG", "false")
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

/// The `src/lib.rs` of a drive crate around `body`: `no_std` with `std` behind the default
/// feature, warnings and missing docs denied.
pub fn no_std_lib(body: &str) -> String {
    format!("//! Generated code under test.\n#![no_std]\n#![deny(warnings, missing_docs)]\n#[cfg(feature = \"std\")]\nextern crate std;\n{body}")
}

/// Builds one scratch crate `crate_name` holding a module of generated code per description, and
/// fails with the compiler's output unless it builds warning-free.
pub fn assert_descriptions_compile(crate_name: &str, descriptions: &[PathBuf]) {
    let modules: String = descriptions
        .iter()
        .map(|path| {
            let module = super::short_name(path).replace('-', "_");
            format!(
                "/// Generated from {module}.\npub mod {module} {{\n{}\n}}\n",
                generated(path)
            )
        })
        .collect();
    let built = build_and_doctest(crate_name, &no_std_lib(&modules));
    assert!(
        built.success,
        "generated code does not build:\n{}",
        built.stderr
    );
}

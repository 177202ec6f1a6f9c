//! `drivegen generate` writes a standalone crate that builds: the Lafert Smartris crate is
//! generated into a temporary folder and built with cargo, drivebus taken from this workspace.

use std::path::Path;
use std::process::Command;

#[test]
fn the_generated_lafert_crate_builds_without_warnings() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::env::temp_dir().join(format!("drivegen-generated-{}", std::process::id()));
    let generate = Command::new(env!("CARGO_BIN_EXE_drivegen"))
        .arg("generate")
        .arg(root.join("descriptions/lafert-smartris"))
        .arg("--out")
        .arg(&out)
        .arg("--drivebus-path")
        .arg(root.join("drivebus").canonicalize().unwrap())
        .output()
        .unwrap();
    assert!(
        generate.status.success(),
        "{}",
        String::from_utf8_lossy(&generate.stderr)
    );
    let manifest = std::fs::read_to_string(out.join("Cargo.toml")).unwrap();
    assert!(
        manifest.contains("name = \"lafert-smartris\""),
        "{manifest}"
    );
    assert!(
        manifest.contains("drivebus = { version = \"0.1\""),
        "{manifest}"
    );

    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let build = Command::new(cargo)
        .args(["build", "--offline", "--quiet", "--manifest-path"])
        .arg(out.join("Cargo.toml"))
        .env("CARGO_TARGET_DIR", root.join("target/generated-crate"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&build.stderr).into_owned();
    std::fs::remove_dir_all(&out).unwrap();
    assert!(
        build.status.success(),
        "the generated crate does not build:\n{stderr}"
    );
    assert!(
        !stderr.contains("warning"),
        "the generated crate has warnings:\n{stderr}"
    );
}

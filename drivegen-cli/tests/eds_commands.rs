//! `drivegen eds export|import` end to end: a shipped description exported as EDS, the EDS
//! imported as an overlay skeleton, and the skeleton valid as it is.

use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_drivegen");

fn run(args: &[&str]) -> std::process::Output {
    Command::new(BIN)
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(".."))
        .output()
        .unwrap()
}

#[test]
fn export_then_import_gives_a_valid_overlay_with_every_object() {
    let dir = std::env::temp_dir().join(format!("drivegen-eds-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let eds = dir.join("lafert.eds");
    let overlay = dir.join("overlay.toml");
    let export = run(&[
        "eds",
        "export",
        "descriptions/lafert-smartris",
        "-o",
        eds.to_str().unwrap(),
    ]);
    assert!(
        export.status.success(),
        "{}",
        String::from_utf8_lossy(&export.stderr)
    );
    let text = std::fs::read_to_string(&eds).unwrap();
    assert!(text.contains("[6041]"), "the statusword is exported");
    let import = run(&[
        "eds",
        "import",
        eds.to_str().unwrap(),
        "-o",
        overlay.to_str().unwrap(),
    ]);
    assert!(
        import.status.success(),
        "{}",
        String::from_utf8_lossy(&import.stderr)
    );
    let check = run(&["check", overlay.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&check.stdout);
    assert!(
        check.status.success(),
        "{}",
        String::from_utf8_lossy(&check.stderr)
    );
    // Every CANopen object of the description and the communication and mapping sub-indices of
    // its PDOs: 122 since issue 27 described RPDO1 / TPDO1, the S-ramp objects 60A3h-60C6h, the
    // error history 1003h and 1017h (86 before).
    assert!(stdout.contains("122 parameters"), "{stdout}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn exporting_a_modbus_only_description_is_refused() {
    let export = run(&["eds", "export", "descriptions/lenze-smd", "-o", "/dev/null"]);
    assert!(!export.status.success());
    assert!(String::from_utf8_lossy(&export.stderr).contains("no CANopen objects"));
}

#[test]
fn import_prints_the_findings_of_the_overlay_and_fails_when_it_does_not_check() {
    let dir = std::env::temp_dir().join(format!("drivegen-eds-import-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("../codegen/tests/eds");
    // A vendor data type: the overlay checks, with a warning naming the object.
    let vendor = dir.join("vendor.toml");
    let eds = corpus.join("data_type_vendor.eds");
    let import = run(&[
        "eds",
        "import",
        eds.to_str().unwrap(),
        "-o",
        vendor.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&import.stderr);
    assert!(import.status.success(), "{stderr}");
    assert!(stderr.contains("DataType 0x0040"), "{stderr}");
    assert!(stderr.contains("the overlay checks as"), "{stderr}");
    // A default outside its limits: the skeleton is written, the error printed, the exit non-zero.
    let odd = dir.join("odd.toml");
    let eds = corpus.join("default_outside_limits.eds");
    let import = run(&[
        "eds",
        "import",
        eds.to_str().unwrap(),
        "-o",
        odd.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&import.stderr);
    assert!(!import.status.success(), "{stderr}");
    assert!(
        stderr.contains("error[defaults_within_range]") && stderr.contains("does not check"),
        "{stderr}"
    );
    assert!(std::fs::read_to_string(&odd)
        .unwrap()
        .contains("index = 0x2000"));
    // To standard output, it is checked as saved beside the EDS.
    let import = run(&["eds", "import", eds.to_str().unwrap()]);
    assert!(!import.status.success());
    assert!(
        String::from_utf8_lossy(&import.stdout).contains("eds = \"default_outside_limits.eds\"")
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

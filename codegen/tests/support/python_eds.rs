//! The independent check of an exported EDS: python canopen loads it and compares its objects
//! with the IR's (`tests/peers/eds_import_check.py`).

use std::path::Path;
use std::process::Command;

use drivegen::ir::Device;
use peer_support::python;

/// Node id python resolves `$NODEID` defaults with.
pub const NODE_ID: u8 = 5;

/// Exports `device` to `eds` (and its IR beside it as JSON) and lets python canopen load it:
/// `Ok` once it compared the objects, else its output.
pub fn python_loads_the_export(device: &Device, eds: &Path) -> Result<(), String> {
    let ir = eds.with_extension("ir.json");
    std::fs::write(eds, drivegen::eds::export(device)).unwrap();
    std::fs::write(&ir, serde_json::to_string(device).unwrap()).unwrap();
    let script = super::workspace_root().join("tests/peers/eds_import_check.py");
    let output = Command::new(python())
        .arg(&script)
        .arg(eds)
        .arg(&ir)
        .arg(NODE_ID.to_string())
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "cannot start {}: {e}; run tests/peers/setup.sh",
                python().display()
            )
        });
    let stdout = String::from_utf8_lossy(&output.stdout);
    match output.status.success() && stdout.contains("objects compared") {
        true => Ok(()),
        false => Err(format!(
            "python canopen: {stdout}\n{}",
            String::from_utf8_lossy(&output.stderr)
        )),
    }
}

//! Runs the whole pipeline on a description written inline.

use crate::diagnostic::Diagnostic;

/// A minimal valid device header; tests append tables to it.
pub const HEADER: &str = r#"format = 1
[device]
name = "Test"
handle = "Test"
[[source]]
id = "m"
file = "manual.txt"
title = "Manual"
"#;

/// The whole check of `HEADER + body`.
pub fn checked(body: &str) -> crate::Checked {
    let dir =
        std::env::temp_dir().join(format!("drivegen-test-{}-{}", std::process::id(), unique()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("device.toml");
    std::fs::write(&path, format!("{HEADER}{body}")).unwrap();
    let checked = crate::check(&path);
    std::fs::remove_dir_all(&dir).unwrap();
    checked
}

/// Diagnostics of `HEADER + body`, keeping only those of `rule`.
pub fn diagnostics(rule: &str, body: &str) -> Vec<Diagnostic> {
    checked(body)
        .diagnostics
        .into_iter()
        .filter(|d| d.rule == rule)
        .collect()
}

/// The device model of `HEADER + body`, which must be valid.
pub fn device(body: &str) -> crate::ir::Device {
    let checked = checked(body);
    match checked.device {
        Some(device) => device,
        None => panic!("invalid test description:\n{}", checked.render()),
    }
}

fn unique() -> u64 {
    use std::sync::atomic::{AtomicU64, Ordering};
    static NEXT: AtomicU64 = AtomicU64::new(0);
    NEXT.fetch_add(1, Ordering::Relaxed)
}

/// Messages of the diagnostics of `rule`.
pub fn messages(rule: &str, body: &str) -> Vec<String> {
    diagnostics(rule, body)
        .into_iter()
        .map(|d| d.message)
        .collect()
}

/// The device model of the description in `descriptions/<name>/device.toml`.
pub fn shipped(name: &str) -> crate::ir::Device {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../descriptions")
        .join(name)
        .join("device.toml");
    crate::check(&path)
        .device
        .unwrap_or_else(|| panic!("{name} is valid"))
}

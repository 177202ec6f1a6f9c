//! A CANopen revision range of any width is checked by the generated `verify_identity`
//! (`drivebus::Covered::Range`, refused with `WriteRefusal::IdentityOutOfRange`), not only
//! ranges short enough to list.

mod support;

use support::crate_build::{build_and_test, generated, no_std_lib};
use support::Scratch;

const DESCRIPTION: &str = r#"format = 1
include = [{ path = "PROFILES/cia301.toml", only = ["device_type", "error_register", "identity_count", "vendor_id", "revision_number"] }]
[device]
name = "Revisions"
handle = "Revisions"
[[source]]
id = "m"
file = "manual.txt"
title = "Manual"
[canopen]
default_node_id = 1
source = { doc = "m", line = 1 }
[identity]
vendor_id = 0x515
revisions = { min = 0x10000, max = 0x2FFFF }
source = { doc = "m", line = 1 }
"#;

#[test]
fn a_wide_revision_range_is_checked_as_a_range() {
    let scratch = Scratch::new("identity-revision-ranges");
    let profiles = support::workspace_root().join("descriptions/profiles");
    let text = DESCRIPTION.replace("PROFILES", profiles.to_str().unwrap());
    let path = scratch.0.join("revisions.toml");
    std::fs::write(&path, text).unwrap();
    let checked = drivegen::check(&path);
    assert!(checked.device.is_some(), "{}", checked.render());
    let code = generated(&path);
    assert!(code.contains("::drivebus::Covered::Range"), "{code}");
    assert!(
        code.contains("min: 65536") && code.contains("max: 196607"),
        "{code}"
    );
    let lib = no_std_lib(&format!(
        "/// Generated.\npub mod revisions {{\n{code}\n}}\n"
    ));
    let built = build_and_test("identity_revision_ranges", &lib, NODE_TEST);
    assert!(built.success, "{}", built.stderr);
}

/// Nodes reporting revisions inside, at the edges of and outside the covered range.
const NODE_TEST: &str = r#"
use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::testing::MemoryBus;
use drivebus::{Error, WriteRefusal};
use identity_revision_ranges::revisions::Revisions;

fn verify(revision: u32) -> Result<(), Error> {
    let mut memory = MemoryBus::new();
    memory.set_object(0x1018, 1, &0x515u32.to_le_bytes());
    memory.set_object(0x1018, 3, &revision.to_le_bytes());
    let mut drive: Revisions<CanOpenLink<MemoryBus>> = Revisions::canopen(memory, NodeId(1));
    drive.verify_identity()
}

#[test]
fn revisions_outside_the_range_are_refused() {
    assert_eq!(verify(0x10000), Ok(()));
    assert_eq!(verify(0x2FFFF), Ok(()));
    assert_eq!(verify(0x1_8000), Ok(()));
    assert_eq!(
        verify(0x30000),
        Err(Error::WritesRefused {
            parameter: "revision_number",
            reason: WriteRefusal::IdentityOutOfRange {
                parameter: "revision_number",
                min: 0x10000,
                max: 0x2FFFF,
                found: 0x30000,
            },
        })
    );
    assert!(verify(0xFFFF).is_err());
}
"#;

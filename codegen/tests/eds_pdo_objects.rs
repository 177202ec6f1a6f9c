//! The PDO objects derived from the ez-Wheel description (SWD user manual v2.0.3,
//! `../shared/seeds/002_7f0dd2fb8f792336.txt`, section 9.7). The description tabulates the
//! objects of every PDO itself (lines 1338-1439, and since issue 27 also those of the PDOs the
//! manual ships mapped but disabled, TPDO 2 and 5-8, lines 1322-1331), so nothing is derived from
//! it; with the disabled PDOs' objects taken out, those are derived, with COB-ID bit 31 set.

mod support;

use drivegen::ir::{Device, MappingKind, Number, Parameter};
use support::{device, workspace_root};

fn ez_wheel() -> Device {
    device(&workspace_root().join("descriptions/ezwheel-swd"))
}

/// The communication and mapping objects of TPDO 2 and 5-8, disabled by default.
const DISABLED_PDO_OBJECTS: [u16; 10] = [
    0x1801, 0x1804, 0x1805, 0x1806, 0x1807, 0x1A01, 0x1A04, 0x1A05, 0x1A06, 0x1A07,
];

/// The ez-Wheel description without the objects of its disabled PDOs, as it was before it
/// described them: the PDOs' own data is what the derivation has.
fn ez_wheel_without_disabled_pdo_objects() -> Device {
    let mut device = ez_wheel();
    let disabled = |index: u16| DISABLED_PDO_OBJECTS.contains(&index);
    device
        .parameters
        .retain(|p| p.canopen.first().is_none_or(|a| !disabled(a.index)));
    device.records.retain(|r| !disabled(r.index));
    device
}

/// The derived parameter at `index` / `subindex`.
fn object(derived: &[Parameter], index: u16, subindex: u8) -> &Parameter {
    derived
        .iter()
        .find(|p| p.canopen[0].index == index && p.canopen[0].subindex == subindex)
        .unwrap_or_else(|| panic!("no object {index:#06X} sub {subindex}"))
}

fn default(derived: &[Parameter], index: u16, subindex: u8) -> (i64, bool) {
    let p = object(derived, index, subindex);
    let Some(Number::Int(value)) = p.default else {
        panic!("{} has no integer default", p.name)
    };
    (value, p.default_plus_node_id)
}

#[test]
fn mapping_objects_of_disabled_pdos_hold_the_manuals_mapping() {
    let derived = drivegen::eds::pdo_objects(&ez_wheel_without_disabled_pdo_objects()).parameters;
    // Lines 1325, 1328-1331: TPDO 2 and 5-8 map the statusword 6041 0010h.
    for mapping in [0x1A01, 0x1A04, 0x1A05, 0x1A06, 0x1A07] {
        assert_eq!(default(&derived, mapping, 0), (1, false));
        assert_eq!(default(&derived, mapping, 1), (0x6041_0010, false));
    }
}

#[test]
fn a_pdo_disabled_by_default_has_cob_id_bit_31_set() {
    let derived = drivegen::eds::pdo_objects(&ez_wheel_without_disabled_pdo_objects()).parameters;
    // The manual gives no COB-ID for TPDO 2: not valid, no identifier, not node-relative.
    assert_eq!(default(&derived, 0x1801, 1), (0x8000_0000, false));
    // Only sub 1 is given: the highest sub-index is 1.
    assert_eq!(default(&derived, 0x1801, 0), (1, false));
    assert!(object(&derived, 0x1801, 1).canopen[0].access.write);
}

#[test]
fn objects_the_description_defines_itself_are_not_derived_again() {
    let complete = drivegen::eds::pdo_objects(&ez_wheel());
    assert!(complete.parameters.is_empty() && complete.records.is_empty());
    let derived = drivegen::eds::pdo_objects(&ez_wheel_without_disabled_pdo_objects());
    for described in [
        0x1400, 0x1403, 0x1600, 0x1603, 0x1800, 0x1802, 0x1803, 0x1A00, 0x1A02,
    ] {
        assert!(derived
            .parameters
            .iter()
            .all(|p| p.canopen[0].index != described));
        assert!(derived.records.iter().all(|r| r.index != described));
    }
    assert_eq!(
        derived.records.len(),
        2 * 5,
        "TPDO 2 and 5-8: communication and mapping"
    );
}

#[test]
fn pdos_validation_would_refuse_are_skipped_not_panicked_on() {
    let mut device = ez_wheel_without_disabled_pdo_objects();
    let disabled: Vec<usize> = (0..device.mappings.len())
        .filter(|&i| device.mappings[i].pdo().is_some() && !device.mappings[i].enabled)
        .collect();
    assert_eq!(disabled.len(), 5);
    for (i, number) in [(disabled[0], 0), (disabled[1], 600)] {
        if let MappingKind::Pdo(pdo) = &mut device.mappings[i].kind {
            pdo.number = number;
        }
    }
    device.mappings[disabled[2]]
        .entries
        .push("no_such_parameter".into());
    let derived = drivegen::eds::pdo_objects(&device);
    assert_eq!(derived.records.len(), 2 * 2);
}

#[test]
fn inhibit_time_and_event_timer_become_sub_indices_3_and_5() {
    let dir = std::env::temp_dir().join(format!("drivegen-pdo-timers-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("device.toml");
    std::fs::write(
        &path,
        r#"format = 1
[device]
name = "Timers"
handle = "Timers"
[[source]]
id = "m"
file = "m.txt"
title = "Manual"

[[parameter]]
name = "statusword"
type = "u16"
canopen = { index = 0x6041, access = "ro", pdo = "tx" }
source = { doc = "m", line = 1 }

[[pdo]]
name = "tpdo1"
direction = "tx"
number = 1
cob_id = "$NODEID+0x180"
enabled = false
transmission_type = 254
inhibit_time = 100
event_timer = 500
entries = ["statusword"]
source = { doc = "m", line = 2 }
"#,
    )
    .unwrap();
    let device = device(&path);
    std::fs::remove_dir_all(&dir).unwrap();
    let derived = drivegen::eds::pdo_objects(&device).parameters;
    assert_eq!(default(&derived, 0x1800, 0), (5, false));
    assert_eq!(default(&derived, 0x1800, 1), (0x8000_0180, true));
    assert_eq!(default(&derived, 0x1800, 2), (254, false));
    assert_eq!(default(&derived, 0x1800, 3), (100, false));
    assert_eq!(default(&derived, 0x1800, 5), (500, false));
}

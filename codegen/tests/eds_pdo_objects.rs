//! The PDO objects derived from the ez-Wheel description equal the manual's own tables of its
//! default PDOs (SWD user manual v2.0.3, `../shared/seeds/002_7f0dd2fb8f792336.txt`, section 9.7,
//! lines 1338–1390).

mod support;

use drivegen::ir::{Device, Number, Parameter};
use support::{device, workspace_root};

fn ez_wheel() -> Device {
    device(&workspace_root().join("descriptions/ezwheel-swd"))
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
fn mapping_objects_hold_the_manuals_mapping_entries() {
    let derived = drivegen::eds::pdo_objects(&ez_wheel()).parameters;
    // Line 1347-1348: 1600h sub 0 = 01h, sub 1 = 6040 0010h (Controlword).
    assert_eq!(default(&derived, 0x1600, 0), (1, false));
    assert_eq!(default(&derived, 0x1600, 1), (0x6040_0010, false));
    // Lines 1368-1370: 1603h sub 0 = 02h, Controlword and vl target velocity 6042 0010h.
    assert_eq!(default(&derived, 0x1603, 0), (2, false));
    assert_eq!(default(&derived, 0x1603, 1), (0x6040_0010, false));
    assert_eq!(default(&derived, 0x1603, 2), (0x6042_0010, false));
    // Lines 1387-1388: 1A00h sub 0 = 01h, sub 1 = 6041 0010h (Statusword).
    assert_eq!(default(&derived, 0x1A00, 0), (1, false));
    assert_eq!(default(&derived, 0x1A00, 1), (0x6041_0010, false));
}

#[test]
fn communication_objects_keep_cob_ids_relative_to_the_node() {
    let derived = drivegen::eds::pdo_objects(&ez_wheel()).parameters;
    // Line 1339: 1400h sub 1 = 0000 0210h at the manual's node 10h, i.e. $NODEID + 200h.
    assert_eq!(default(&derived, 0x1400, 1), (0x200, true));
    // Line 1384: 1800h sub 1 = 4000 0190h (no RTR) at node 10h.
    assert_eq!(default(&derived, 0x1800, 1), (0x4000_0180, true));
    // Lines 1338 and 1340: two entries, transmission type 01h.
    assert_eq!(default(&derived, 0x1400, 0), (2, false));
    assert_eq!(default(&derived, 0x1400, 2), (1, false));
    assert!(!object(&derived, 0x1400, 0).canopen[0].access.write);
    assert!(object(&derived, 0x1400, 1).canopen[0].access.write);
}

#[test]
fn objects_the_description_defines_itself_are_not_derived_again() {
    let mut device = ez_wheel();
    let derived = drivegen::eds::pdo_objects(&device);
    let rpdo1_mapping = derived
        .parameters
        .iter()
        .find(|p| p.canopen[0].index == 0x1600)
        .cloned()
        .expect("derived 0x1600");
    device.parameters.push(rpdo1_mapping);
    let again = drivegen::eds::pdo_objects(&device);
    assert!(again
        .parameters
        .iter()
        .all(|p| p.canopen[0].index != 0x1600));
    assert!(again.records.iter().all(|r| r.index != 0x1600));
    assert!(again
        .parameters
        .iter()
        .any(|p| p.canopen[0].index == 0x1400));
}

#[test]
fn pdos_validation_would_refuse_are_skipped_not_panicked_on() {
    let mut device = ez_wheel();
    let pdos = device.pdos.len();
    assert!(pdos >= 3, "ez-Wheel declares its default PDOs");
    device.pdos[0].number = 0;
    device.pdos[1].number = 600;
    device.pdos[2].entries.push("no_such_parameter".into());
    let derived = drivegen::eds::pdo_objects(&device);
    assert_eq!(derived.records.len(), 2 * (pdos - 3));
}

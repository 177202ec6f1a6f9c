//! Every object the manual lists with an address (tests/manual_object_list.txt, with manual line
//! numbers) is in the description, as `drivegen::check` reads it: over CANopen and RS-232 at its
//! index and subindex (line 1923: the RS-232 address is the CANopen one) and, where the manual
//! gives a Modbus register, at that register. Objects the description decides against
//! (ERRATA.md) must stay out. And every property of every described parameter (type, access,
//! PDO mapping, unit, scale, range, default, allowed and enumerated values, bits) is the one
//! tests/manual_table.txt types from the manual, compared by the `manual-table` crate.

use std::collections::BTreeSet;
use std::path::Path;

use drivegen::ir::Device;

/// One line of the list.
#[derive(Debug)]
struct Listed {
    index: u16,
    subindex: u8,
    modbus: Option<u16>,
    manual_line: u32,
    described: bool,
}

fn hex<T: TryFrom<u32>>(text: &str) -> T {
    let value = u32::from_str_radix(text, 16).unwrap_or_else(|e| panic!("{text:?}: {e}"));
    T::try_from(value).unwrap_or_else(|_| panic!("{text:?} out of range"))
}

fn manual_list() -> Vec<Listed> {
    include_str!("manual_object_list.txt")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(
            |line| match line.split_whitespace().collect::<Vec<_>>()[..] {
                [index, subindex, modbus, manual_line, state] => Listed {
                    index: hex(index),
                    subindex: hex(subindex),
                    modbus: (modbus != "-").then(|| hex(modbus)),
                    manual_line: manual_line.parse().unwrap(),
                    described: match state {
                        "described" => true,
                        "rejected" => false,
                        other => panic!("unknown state {other:?} in {line:?}"),
                    },
                },
                _ => panic!("cannot read {line:?}"),
            },
        )
        .collect()
}

fn description() -> Device {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../descriptions/kinco-fd");
    let checked = drivegen::check(&path);
    let report = checked.render();
    checked.device.unwrap_or_else(|| panic!("{report}"))
}

#[test]
fn the_list_is_the_manuals() {
    let list = manual_list();
    assert_eq!(list.iter().filter(|l| l.described).count(), 136);
    assert_eq!(list.iter().filter(|l| l.modbus.is_some()).count(), 88);
}

#[test]
fn every_listed_object_is_described_and_every_rejected_one_is_not() {
    let device = description();
    let objects = |pick: fn(&drivegen::ir::Parameter) -> &Vec<drivegen::ir::ObjectAddress>| {
        device
            .parameters
            .iter()
            .flat_map(pick)
            .map(|a| (a.index, a.subindex))
            .collect::<BTreeSet<_>>()
    };
    let canopen = objects(|p| &p.canopen);
    let rs232 = objects(|p| &p.rs232);
    let registers: BTreeSet<(u16, u16, u8)> = device
        .parameters
        .iter()
        .flat_map(|p| {
            p.canopen.iter().flat_map(move |c| {
                p.modbus
                    .iter()
                    .map(move |m| (m.address, c.index, c.subindex))
            })
        })
        .collect();
    let mut wrong = Vec::new();
    for entry in manual_list() {
        let key = (entry.index, entry.subindex);
        let on_modbus = entry
            .modbus
            .is_none_or(|m| registers.contains(&(m, entry.index, entry.subindex)));
        let present = canopen.contains(&key) && rs232.contains(&key) && on_modbus;
        let absent = !canopen.contains(&key) && !rs232.contains(&key);
        if (entry.described && !present) || (!entry.described && !absent) {
            wrong.push(format!(
                "manual line {}: {:04X}h.{:02X} (Modbus {:X?}) should be {}",
                entry.manual_line,
                entry.index,
                entry.subindex,
                entry.modbus,
                if entry.described {
                    "described"
                } else {
                    "left out"
                }
            ));
        }
    }
    assert!(wrong.is_empty(), "not as listed:\n{}", wrong.join("\n"));
}

#[test]
fn every_modbus_register_has_one_object() {
    // Appendix 3 gives 0x6810 to the chopping voltage as well as to Kpp (ERRATA.md #16).
    let device = description();
    let mut seen = BTreeSet::new();
    for p in &device.parameters {
        // A read-back is its owner's register, no object of its own (ERRATA.md #51).
        for m in p.modbus.iter().filter(|m| m.read_back_of.is_none()) {
            assert!(
                seen.insert(m.address),
                "{:#06x} twice ({})",
                m.address,
                p.name
            );
        }
    }
    assert!(seen.contains(&0x6810));
    let read_backs: Vec<(&str, u16, Option<&str>)> = device
        .parameters
        .iter()
        .flat_map(|p| p.modbus.iter().map(move |m| (p, m)))
        .filter(|(_, m)| m.read_back_of.is_some())
        .map(|(p, m)| (p.name.as_str(), m.address, m.read_back_of.as_deref()))
        .collect();
    assert_eq!(
        read_backs,
        [(
            "modes_of_operation_display",
            0x3500,
            Some("modes_of_operation")
        )]
    );
}

/// Parameters the description includes from the CiA 301 profile whose values the manual does
/// not give (COVERAGE.md, "CiA 301 mandatory objects"): no manual row to compare.
const NOT_IN_THE_MANUAL: [&str; 3] = ["device_type", "error_register", "identity_count"];

fn manual_table() -> Vec<manual_table::Row> {
    manual_table::parse(include_str!("manual_table.txt"))
}

#[test]
fn every_property_is_the_manuals() {
    let differences = manual_table::compare(&description(), &manual_table());
    assert!(
        differences.is_empty(),
        "the description differs from the manual table (tests/manual_table.txt):\n{}",
        differences.join("\n")
    );
}

#[test]
fn every_described_parameter_has_a_row() {
    let rows: BTreeSet<String> = manual_table().into_iter().map(|r| r.name).collect();
    let device = description();
    let without: Vec<&str> = device
        .parameters
        .iter()
        .map(|p| p.name.as_str())
        .filter(|name| !rows.contains(*name) && !NOT_IN_THE_MANUAL.contains(name))
        .collect();
    assert!(without.is_empty(), "no manual row for {without:?}");
    assert_eq!(
        rows.len(),
        device.parameters.len() - NOT_IN_THE_MANUAL.len()
    );
}

#[test]
fn a_wrong_default_in_the_table_is_caught() {
    // The comparison can fail: the manual's Max speed default (5000 rpm, line 1965) changed by one.
    let mut rows = manual_table();
    let row = rows.iter_mut().find(|r| r.name == "max_speed").unwrap();
    row.properties.insert("default".into(), "5001".into());
    assert_eq!(
        manual_table::compare(&description(), &rows),
        ["`max_speed` default: the manual (line 1965) gives 5001, the description 5000"]
    );
}

//! Every register and object the manuals list (tests/manual_register_list.txt, with manual line
//! numbers) must be in the description, as `drivegen::check` reads it; objects the description
//! deliberately leaves out are listed with the reason and must stay out until the list says
//! otherwise. Every property of every described parameter — addresses with access, type, unit,
//! scale, range, default, allowed and enum values, bits, bounds, PDO mapping — must equal the row
//! typed from the manuals in tests/manual_table.txt (`manual_table::compare`).

use std::collections::BTreeSet;
use std::path::Path;

use drivegen::ir::{Device, Table};
use manual_table::Row;

/// One entry of the list.
#[derive(Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Listed {
    Register { input: bool, address: u16 },
    Object { index: u16, described: bool },
}

fn number(text: &str) -> u16 {
    u16::from_str_radix(text.trim_start_matches("0x"), 16)
        .unwrap_or_else(|e| panic!("bad hex number {text:?}: {e}"))
}

/// The list, with the line of the list file of each entry.
fn manual_list() -> Vec<(usize, Listed)> {
    let text = include_str!("manual_register_list.txt");
    text.lines()
        .enumerate()
        .filter(|(_, line)| !line.starts_with('#') && !line.trim().is_empty())
        .map(|(i, line)| {
            let fields: Vec<&str> = line.split_whitespace().collect();
            let entry = match fields.as_slice() {
                ["modbus", table, address, ..] => Listed::Register {
                    input: *table == "input",
                    address: number(address),
                },
                ["canopen", index, _, state, ..] => Listed::Object {
                    index: number(index),
                    described: *state == "described",
                },
                _ => panic!("line {}: cannot read {line:?}", i + 1),
            };
            (i + 1, entry)
        })
        .collect()
}

fn description() -> Device {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../descriptions/lafert-smartris");
    let checked = drivegen::check(&path);
    let report = checked.render();
    checked.device.unwrap_or_else(|| panic!("{report}"))
}

/// Every (input?, register) a Modbus address of the description covers, all words included.
fn described_registers(device: &Device) -> BTreeSet<(bool, u16)> {
    device
        .parameters
        .iter()
        .flat_map(|p| &p.modbus)
        .flat_map(|a| (0..a.words).map(move |w| (a.table == Table::Input, a.address + w)))
        .collect()
}

fn described_objects(device: &Device) -> BTreeSet<u16> {
    device
        .parameters
        .iter()
        .flat_map(|p| &p.canopen)
        .map(|a| a.index)
        .collect()
}

#[test]
fn every_listed_register_and_object_is_described() {
    let device = description();
    let registers = described_registers(&device);
    let objects = described_objects(&device);
    let missing: Vec<String> = manual_list()
        .into_iter()
        .filter(|(_, entry)| match entry {
            Listed::Register { input, address } => !registers.contains(&(*input, *address)),
            Listed::Object { index, described } => *described && !objects.contains(index),
        })
        .map(|(line, entry)| format!("list line {line}: {entry:?}"))
        .collect();
    assert!(missing.is_empty(), "not in the description: {missing:#?}");
}

#[test]
fn objects_listed_as_left_out_are_not_described() {
    let objects = described_objects(&description());
    let stale: Vec<u16> = manual_list()
        .into_iter()
        .filter_map(|(_, entry)| match entry {
            Listed::Object {
                index,
                described: false,
            } if objects.contains(&index) => Some(index),
            _ => None,
        })
        .collect();
    assert!(
        stale.is_empty(),
        "described now; update manual_register_list.txt and COVERAGE.md: {stale:04X?}"
    );
}

#[test]
fn every_described_register_is_in_a_manual_list() {
    let listed: BTreeSet<(bool, u16)> = manual_list()
        .into_iter()
        .filter_map(|(_, entry)| match entry {
            Listed::Register { input, address } => Some((input, address)),
            Listed::Object { .. } => None,
        })
        .collect();
    let unlisted: Vec<_> = described_registers(&description())
        .difference(&listed)
        .copied()
        .collect();
    assert!(
        unlisted.is_empty(),
        "described but in no list: {unlisted:04X?}"
    );
}

/// The table typed from the manuals, in their notation (`manual_table::notation`).
fn manual_rows() -> Vec<Row> {
    manual_table::parse(include_str!("manual_table.txt"))
}

#[test]
fn every_property_of_every_parameter_is_the_manuals() {
    let differences = manual_table::compare(&description(), &manual_rows());
    assert!(
        differences.is_empty(),
        "the description differs from the manuals (tests/manual_table.txt):\n{}",
        differences.join("\n")
    );
}

#[test]
fn every_described_parameter_has_a_row_and_no_row_is_repeated() {
    let rows = manual_rows();
    let mut named = BTreeSet::new();
    let repeated: Vec<&str> = rows
        .iter()
        .filter(|row| !named.insert(row.name.as_str()))
        .map(|row| row.name.as_str())
        .collect();
    assert!(repeated.is_empty(), "rows given twice: {repeated:?}");
    let without_row: Vec<String> = description()
        .parameters
        .iter()
        .filter(|p| !named.contains(p.name.as_str()))
        .map(|p| p.name.clone())
        .collect();
    assert!(
        without_row.is_empty(),
        "described but not in manual_table.txt: {without_row:?}"
    );
}

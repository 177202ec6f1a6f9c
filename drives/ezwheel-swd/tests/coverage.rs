//! Every object the SWD manual lists (tests/manual_object_list.txt, with manual line numbers)
//! must be in the description as `drivegen::check` reads it: every sub-index of a full table row,
//! every object the description takes from a profile; objects listed as only named must stay out
//! until the list (and COVERAGE.md) says otherwise.

use std::collections::BTreeSet;
use std::path::Path;

use drivegen::ir::Device;

/// One entry of the list.
#[derive(Debug, PartialEq, Eq)]
enum Listed {
    /// A table row: the object and the sub-indices it covers.
    Row { index: u16, subindices: Vec<u8> },
    /// An object named without a row but described from a profile or the text.
    NamedDescribed { index: u16 },
    /// An object only named: not described.
    Undescribed { index: u16 },
}

fn hex(text: &str) -> u16 {
    u16::from_str_radix(text.trim_start_matches("0x"), 16)
        .unwrap_or_else(|e| panic!("bad index {text:?}: {e}"))
}

/// `"3"` or `"1..=8"`.
fn subindices(text: &str) -> Vec<u8> {
    let number = |t: &str| {
        t.parse::<u8>()
            .unwrap_or_else(|e| panic!("bad sub-index {t:?}: {e}"))
    };
    match text.split_once("..=") {
        Some((first, last)) => (number(first)..=number(last)).collect(),
        None => vec![number(text)],
    }
}

/// The list, with the line of the list file of each entry.
fn manual_list() -> Vec<(usize, Listed)> {
    include_str!("manual_object_list.txt")
        .lines()
        .enumerate()
        .filter(|(_, line)| !line.starts_with('#') && !line.trim().is_empty())
        .map(|(i, line)| {
            let fields: Vec<&str> = line.split_whitespace().collect();
            let entry = match fields.as_slice() {
                ["canopen", index, sub, _, "described", ..] => Listed::Row {
                    index: hex(index),
                    subindices: subindices(sub),
                },
                ["canopen", index, "-", _, "named-described", ..] => {
                    Listed::NamedDescribed { index: hex(index) }
                }
                ["canopen", index, "-", _, "undescribed:", ..] => {
                    Listed::Undescribed { index: hex(index) }
                }
                _ => panic!("line {}: cannot read {line:?}", i + 1),
            };
            (i + 1, entry)
        })
        .collect()
}

fn description() -> Device {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../descriptions/ezwheel-swd");
    let checked = drivegen::check(&path);
    let report = checked.render();
    checked.device.unwrap_or_else(|| panic!("{report}"))
}

fn described(device: &Device) -> BTreeSet<(u16, u8)> {
    device
        .parameters
        .iter()
        .flat_map(|p| &p.canopen)
        .map(|a| (a.index, a.subindex))
        .collect()
}

#[test]
fn every_listed_row_and_named_object_is_described() {
    let objects = described(&description());
    let has_index = |index: u16| {
        objects
            .range((index, 0)..=(index, u8::MAX))
            .next()
            .is_some()
    };
    let missing: Vec<String> = manual_list()
        .into_iter()
        .flat_map(|(line, entry)| {
            let absent: Vec<String> = match &entry {
                Listed::Row { index, subindices } => subindices
                    .iter()
                    .filter(|s| !objects.contains(&(*index, **s)))
                    .map(|s| format!("list line {line}: {index:04X}:{s}"))
                    .collect(),
                Listed::NamedDescribed { index } if !has_index(*index) => {
                    vec![format!("list line {line}: {index:04X}")]
                }
                _ => Vec::new(),
            };
            absent
        })
        .collect();
    assert!(missing.is_empty(), "not in the description: {missing:#?}");
}

#[test]
fn objects_listed_as_only_named_are_not_described() {
    let objects = described(&description());
    let stale: Vec<u16> = manual_list()
        .into_iter()
        .filter_map(|(_, entry)| match entry {
            Listed::Undescribed { index }
                if objects
                    .range((index, 0)..=(index, u8::MAX))
                    .next()
                    .is_some() =>
            {
                Some(index)
            }
            _ => None,
        })
        .collect();
    assert!(
        stale.is_empty(),
        "described now; update manual_object_list.txt and COVERAGE.md: {stale:04X?}"
    );
}

#[test]
fn every_described_object_is_in_the_list() {
    let listed: BTreeSet<u16> = manual_list()
        .into_iter()
        .filter_map(|(_, entry)| match entry {
            Listed::Row { index, .. } | Listed::NamedDescribed { index } => Some(index),
            Listed::Undescribed { .. } => None,
        })
        .collect();
    let unlisted: BTreeSet<u16> = described(&description())
        .into_iter()
        .map(|(index, _)| index)
        .filter(|index| !listed.contains(index))
        .collect();
    assert!(
        unlisted.is_empty(),
        "described but in no list: {unlisted:04X?}"
    );
}

#[test]
fn the_list_counts_the_manuals_tables() {
    // 118 objects with table rows between lines 1013 and 3600. Issue 19 counts 119: the heading
    // "66F1h to 66F8h" (line 3045) also covers 66F8h, which is safety statusword 1 with its own
    // table (line 3078); see ERRATA.md.
    let rows: BTreeSet<u16> = manual_list()
        .into_iter()
        .filter_map(|(_, entry)| match entry {
            Listed::Row { index, .. } => Some(index),
            _ => None,
        })
        .collect();
    assert_eq!(rows.len(), 118);
}

//! Every object the SWD manual lists (tests/manual_object_list.txt, with manual line numbers)
//! must be in the description as `drivegen::check` reads it: every sub-index of a full table row,
//! every object the description takes from a profile; objects listed as only named must stay out
//! until the list (and COVERAGE.md) says otherwise.
//!
//! And every property of every described parameter must be the manual's: tests/manual_table.txt
//! holds one row per described parameter typed from the manual (address and access, PDO
//! mapping, type, unit, scale, range, default, allowed values, enumeration values, bits), each
//! with the manual line it was typed from, and `manual_table::compare` must find no difference.
//! Where the description decides against a printed value, the row gives the decided value and
//! its comment the printed one and the erratum (ERRATA.md and the description's `erratum`).

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

/// Expands the table's sub-index runs: a row named `name_{A..=B}` stands for the rows `name_A` ...
/// `name_B` (the description's members of a run), with `{sub}` in the row replaced by each
/// sub-index in two hex digits. The bounds are typed from the manual's "01h to 08h" like every
/// other value.
fn expand_runs(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let run = line.split_whitespace().next().and_then(|name| {
            let (_, rest) = name.split_once('{')?;
            let (first, last) = rest.strip_suffix('}')?.split_once("..=")?;
            Some((
                first.parse::<u8>().ok()?,
                last.parse::<u8>().ok()?,
                format!("{{{rest}"),
            ))
        });
        match run {
            None => {
                out.push_str(line);
                out.push('\n');
            }
            Some((first, last, pattern)) => {
                for sub in first..=last {
                    let row = line
                        .replacen(&pattern, &sub.to_string(), 1)
                        .replace("{sub}", &format!("{sub:02X}"));
                    out.push_str(&row);
                    out.push('\n');
                }
            }
        }
    }
    out
}

/// The manual's property table, runs expanded.
fn manual_table() -> Vec<manual_table::Row> {
    manual_table::parse(&expand_runs(include_str!("manual_table.txt")))
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

#[test]
fn every_property_of_every_described_parameter_is_the_manuals() {
    let differences = manual_table::compare(&description(), &manual_table());
    assert!(
        differences.is_empty(),
        "{} differences between tests/manual_table.txt and the description:\n{}",
        differences.len(),
        differences.join("\n")
    );
}

#[test]
fn every_described_parameter_has_a_row_in_the_manual_table() {
    let rows: BTreeSet<String> = manual_table().into_iter().map(|row| row.name).collect();
    let device = description();
    let without: Vec<&str> = device
        .parameters
        .iter()
        .map(|p| p.name.as_str())
        .filter(|name| !rows.contains(*name))
        .collect();
    assert!(
        without.is_empty(),
        "described without a row in tests/manual_table.txt: {without:#?}"
    );
}

#[test]
fn a_run_row_expands_to_one_row_per_sub_index() {
    let rows = manual_table::parse(&expand_runs(
        "sls_command_{1..=3} canopen=6690.{sub}:r pdo=none type=bool line=3397",
    ));
    let names: Vec<&str> = rows.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(names, ["sls_command_1", "sls_command_2", "sls_command_3"]);
    assert_eq!(rows[2].properties["canopen"], "6690.03:r");
    assert_eq!(rows[2].line, 3397);
}

#[test]
fn a_wrong_value_in_the_description_fails_the_comparison() {
    // The comparison can fail: the row of 6502h with another default than the description's.
    let rows = manual_table::parse(
        "supported_drive_modes canopen=6502.00:r pdo=none type=u32 range=2..2 default=3 bits=0,1,2,3,5,6,7,8,9,10 line=2453",
    );
    let differences = manual_table::compare(&description(), &rows);
    assert!(
        differences.iter().any(|d| d.contains("default")),
        "{differences:#?}"
    );
}

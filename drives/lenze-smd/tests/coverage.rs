//! Every register the manual lists (tests/manual_register_list.txt, with manual line numbers) is
//! described in the configuration it belongs to, with the word count a read of it returns, and
//! nothing else is described. Also checks the counts the issue and COVERAGE.md state about the two
//! configurations, so a miscounted list cannot pass. Every property of every parameter (address
//! per configuration, access, type, unit, scale, range, default, enum values, bit fields, bounds)
//! equals the manual's, as typed by hand into tests/manual_table.txt.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use drivegen::ir::Device;

const CONFIGURATIONS: [&str; 2] = ["pc400", "pc507"];

/// One list entry: configuration, register, words, manual code.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Listed {
    configuration: String,
    register: u16,
    words: u16,
    code: String,
}

fn manual_list() -> Vec<(usize, Listed)> {
    include_str!("manual_register_list.txt")
        .lines()
        .enumerate()
        .filter(|(_, line)| !line.starts_with('#') && !line.trim().is_empty())
        .map(|(i, line)| {
            let fields: Vec<&str> = line.split_whitespace().collect();
            let [configuration, register, words, _line, code, ..] = fields.as_slice() else {
                panic!("list line {}: cannot read {line:?}", i + 1)
            };
            let number = |text: &str| {
                text.parse::<u16>()
                    .unwrap_or_else(|e| panic!("list line {}: {text:?}: {e}", i + 1))
            };
            let entry = Listed {
                configuration: configuration.to_string(),
                register: number(register),
                words: number(words),
                code: code.to_string(),
            };
            (i + 1, entry)
        })
        .collect()
}

/// The (configuration, register) pairs an entry stands for.
fn placements(entry: &Listed) -> Vec<(String, u16, u16)> {
    let configurations: Vec<&str> = match entry.configuration.as_str() {
        "both" => CONFIGURATIONS.to_vec(),
        one => vec![one],
    };
    configurations
        .into_iter()
        .map(|c| (c.to_owned(), entry.register, entry.words))
        .collect()
}

fn description() -> Device {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../descriptions/lenze-smd");
    let checked = drivegen::check(&path);
    let report = checked.render();
    checked.device.unwrap_or_else(|| panic!("{report}"))
}

/// Every (configuration, register, words) a Modbus address of the description is active at.
fn described(device: &Device) -> BTreeSet<(String, u16, u16)> {
    let mut out = BTreeSet::new();
    for p in &device.parameters {
        for a in &p.modbus {
            for c in CONFIGURATIONS {
                let active = match &a.variant {
                    Some(v) => v == c,
                    None => p.variants.is_empty() || p.variants.iter().any(|v| v == c),
                };
                if active {
                    out.insert((c.to_owned(), a.address, a.words));
                }
            }
        }
    }
    out
}

#[test]
fn every_listed_register_is_described_in_its_configuration() {
    let described = described(&description());
    let missing: Vec<String> = manual_list()
        .iter()
        .flat_map(|(line, entry)| placements(entry).into_iter().map(move |p| (line, p)))
        .filter(|(_, p)| !described.contains(p))
        .map(|(line, p)| format!("list line {line}: {p:?}"))
        .collect();
    assert!(missing.is_empty(), "not in the description: {missing:#?}");
}

#[test]
fn every_described_register_is_in_the_list() {
    let listed: BTreeSet<(String, u16, u16)> = manual_list()
        .iter()
        .flat_map(|(_, entry)| placements(entry))
        .collect();
    let unlisted: Vec<_> = described(&description())
        .difference(&listed)
        .cloned()
        .collect();
    assert!(
        unlisted.is_empty(),
        "described but not listed: {unlisted:?}"
    );
}

/// A parameter's register in PC400 and in PC507, if it exists there.
type Registers = (Option<u16>, Option<u16>);

/// The section 6.2 parameters, by code.
fn programming_parameters() -> BTreeMap<String, Registers> {
    let mut out: BTreeMap<String, Registers> = BTreeMap::new();
    for (_, entry) in manual_list() {
        let slot = out.entry(entry.code.clone()).or_default();
        match entry.configuration.as_str() {
            "pc400" => slot.0 = Some(entry.register),
            "pc507" => slot.1 = Some(entry.register),
            _ => {}
        }
    }
    out.retain(|_, (pc400, pc507)| pc400.is_some() || pc507.is_some());
    out
}

#[test]
fn the_two_configurations_count_as_the_manual_does() {
    let list = programming_parameters();
    let both = list.values().filter(|(a, b)| a.is_some() && b.is_some());
    let same = both.clone().filter(|(a, b)| a == b).count();
    let pc507_only = list.values().filter(|(a, _)| a.is_none()).count();
    let pc400_only = list.values().filter(|(_, b)| b.is_none()).count();
    assert_eq!(list.len(), 67, "section 6.2 lists 67 parameters");
    assert_eq!(both.count(), 51, "51 exist in both configurations");
    assert_eq!(same, 19, "19 keep their register");
    assert_eq!(pc507_only, 16, "16 exist only in PC507");
    assert_eq!(pc400_only, 0, "none exists only in PC400");
    let by_register = |pick: fn(&Registers) -> Option<u16>| {
        list.iter()
            .filter_map(|(code, r)| pick(r).map(|r| (r, code.clone())))
            .collect::<BTreeMap<u16, String>>()
    };
    let (pc400, pc507) = (by_register(|r| r.0), by_register(|r| r.1));
    let reused = pc400
        .iter()
        .filter(|(r, code)| pc507.get(r).is_some_and(|other| other != *code))
        .count();
    assert_eq!(reused, 26, "26 register numbers mean different parameters");
    assert_eq!(pc400.get(&95).map(String::as_str), Some("c25"));
    assert_eq!(pc507.get(&95).map(String::as_str), Some("C99"));
}

#[test]
fn only_c99_is_a_multi_word_read_at_one_register() {
    let device = description();
    let packed: Vec<(&str, u16, u16, u16)> = device
        .parameters
        .iter()
        .flat_map(|p| p.modbus.iter().map(move |a| (p, a)))
        .filter(|(_, a)| a.words != 1 || a.occupies != 1)
        .map(|(p, a)| (p.name.as_str(), a.address, a.words, a.occupies))
        .collect();
    assert_eq!(
        packed,
        [
            ("software_version", 89, 4, 1),
            ("software_version", 95, 4, 1)
        ]
    );
}

fn manual_table() -> Vec<manual_table::Row> {
    manual_table::parse(include_str!("manual_table.txt"))
}

#[test]
fn every_property_is_the_manuals() {
    let differences = manual_table::compare(&description(), &manual_table());
    assert!(differences.is_empty(), "{differences:#?}");
}

#[test]
fn every_described_parameter_has_a_row_of_the_manual_table() {
    let rows: BTreeSet<String> = manual_table().into_iter().map(|r| r.name).collect();
    let device = description();
    let missing: Vec<&str> = device
        .parameters
        .iter()
        .map(|p| p.name.as_str())
        .filter(|name| !rows.contains(*name))
        .collect();
    assert!(
        missing.is_empty(),
        "no row in manual_table.txt: {missing:?}"
    );
    assert_eq!(rows.len(), device.parameters.len(), "one row per parameter");
}

/// The comparison is not vacuous: a table with one wrong default, one missing range and one
/// extra enum value fails, naming each.
#[test]
fn a_wrong_row_is_reported() {
    let table = include_str!("manual_table.txt")
        .replace("range=75..2400 default=500", "range=75..2400 default=600")
        .replace("unit=ms range=50..65535 default=50", "unit=ms default=50")
        .replace("values=400,507", "values=400,507,508");
    let differences = manual_table::compare(&description(), &manual_table::parse(&table));
    assert_eq!(differences.len(), 3, "{differences:#?}");
    for name in [
        "maximum_output_frequency",
        "serial_fault_time",
        "parameter_configuration",
    ] {
        assert!(
            differences.iter().any(|d| d.contains(name)),
            "{name} not reported: {differences:#?}"
        );
    }
}

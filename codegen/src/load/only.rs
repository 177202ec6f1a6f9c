//! `only` of an include: which parameters, enums, flags types and records of an included profile
//! a description keeps.
//!
//! A list of names keeps those items and what the kept parameters and flags refer to (their
//! enums, flags types and records). A table `{ parameters, enums, flags, records }` selects each
//! kind independently and exactly: a description can take a profile's `modes_of_operation`
//! parameter but declare its own `modes_of_operation` enum with the modes its drive has.

use std::collections::BTreeSet;

use super::raw::{RawFile, RawOnly, RawOnlyKinds};
use super::LoadedFile;
use crate::diagnostic::Diagnostic;

/// The kinds of item `only` selects.
#[derive(Debug, Clone, Copy)]
pub(super) enum Kind {
    Parameter,
    Enum,
    Flags,
    Record,
}

/// Which items of an included file are kept (`None`: all of them).
pub(super) struct Filter(Option<[BTreeSet<String>; 4]>);

impl Filter {
    /// The filter of `file`; names it does not define are reported.
    pub(super) fn new(file: &LoadedFile, diagnostics: &mut Vec<Diagnostic>) -> Filter {
        let raw = &file.raw;
        let sets = match &file.only {
            None => return Filter(None),
            Some(RawOnly::Names(names)) => {
                let keep = with_references(names, raw);
                report_unknown(names, &defined(raw, None), diagnostics);
                [keep.clone(), keep.clone(), keep.clone(), keep]
            }
            Some(RawOnly::Kinds(kinds)) => exact(kinds, raw, diagnostics),
        };
        Filter(Some(sets))
    }

    /// Whether the item `name` of kind `kind` is kept.
    pub(super) fn keeps(&self, kind: Kind, name: &str) -> bool {
        self.0
            .as_ref()
            .is_none_or(|sets| sets[kind as usize].contains(name))
    }
}

/// `names` plus the enums, flags types and records kept parameters and flags refer to.
fn with_references(names: &[String], raw: &RawFile) -> BTreeSet<String> {
    let mut keep: BTreeSet<String> = names.iter().cloned().collect();
    let referenced: Vec<String> = raw
        .parameter
        .iter()
        .filter(|p| keep.contains(p.name.get_ref()))
        .flat_map(|p| {
            [&p.enumeration, &p.flags, &p.record]
                .into_iter()
                .flatten()
                .map(|r| r.get_ref().clone())
        })
        .collect();
    keep.extend(referenced);
    let field_enums: Vec<String> = raw
        .flags
        .iter()
        .filter(|f| keep.contains(f.name.get_ref()))
        .flat_map(|f| {
            f.fields
                .iter()
                .filter_map(|x| x.get_ref().enumeration.as_ref())
                .map(|e| e.get_ref().clone())
        })
        .collect();
    keep.extend(field_enums);
    keep
}

/// One exact set per kind.
fn exact(
    kinds: &RawOnlyKinds,
    raw: &RawFile,
    diagnostics: &mut Vec<Diagnostic>,
) -> [BTreeSet<String>; 4] {
    let lists = [
        (&kinds.parameters, Kind::Parameter),
        (&kinds.enums, Kind::Enum),
        (&kinds.flags, Kind::Flags),
        (&kinds.records, Kind::Record),
    ];
    lists.map(|(names, kind)| {
        report_unknown(names, &defined(raw, Some(kind)), diagnostics);
        names.iter().cloned().collect()
    })
}

/// The names `raw` defines of `kind` (all kinds for `None`).
fn defined(raw: &RawFile, kind: Option<Kind>) -> BTreeSet<&String> {
    let wants = |k: Kind| kind.is_none_or(|want| want as usize == k as usize);
    let mut names = BTreeSet::new();
    if wants(Kind::Parameter) {
        names.extend(raw.parameter.iter().map(|p| p.name.get_ref()));
    }
    if wants(Kind::Enum) {
        names.extend(raw.enums.iter().map(|e| e.name.get_ref()));
    }
    if wants(Kind::Flags) {
        names.extend(raw.flags.iter().map(|f| f.name.get_ref()));
    }
    if wants(Kind::Record) {
        names.extend(raw.record.iter().map(|r| r.name.get_ref()));
    }
    names
}

fn report_unknown(names: &[String], known: &BTreeSet<&String>, out: &mut Vec<Diagnostic>) {
    for name in names.iter().filter(|n| !known.contains(n)) {
        out.push(
            Diagnostic::error_at_no_place(
                "includes_resolve",
                format!("`only` names `{name}`, which the included profile does not define"),
            )
            .help("check the spelling against the profile file (and, in a table, the kind)"),
        );
    }
}

//! What changed between two versions of a description, and whether it breaks code written against
//! the old generated API (`drivegen diff old new`).
//!
//! Every change has an [`Impact`]: *breaking* when code using the old crate may stop compiling
//! (a marker, constant or capability disappears, a value type changes), *behaviour* when it still
//! compiles but reads or writes differently (an address, scale, range or default moved), and
//! *compatible* for pure additions.

mod locks;
mod mappings;
mod models;
mod parameters;
#[cfg(test)]
mod tests;
mod types;

use serde::Serialize;

use crate::ir::Device;

/// How a change affects code written against the old generated crate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Impact {
    /// Code using the old API may no longer compile.
    Breaking,
    /// Code still compiles, but values are read, written or checked differently.
    Behaviour,
    /// Something was added; existing code is unaffected.
    Compatible,
}

/// One difference between two descriptions.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Change {
    /// How it affects existing code.
    pub impact: Impact,
    /// What changed: ``parameter `bus_dc_link` ``, ``enum `baud_rate` ``, ...
    pub subject: String,
    /// The change, in words.
    pub what: String,
}

impl Change {
    fn new(impact: Impact, subject: impl Into<String>, what: impl Into<String>) -> Self {
        Self {
            impact,
            subject: subject.into(),
            what: what.into(),
        }
    }
}

/// Every change from `old` to `new`, breaking ones first, then by subject.
pub fn diff(old: &Device, new: &Device) -> Vec<Change> {
    let mut changes = Vec::new();
    types::device(old, new, &mut changes);
    parameters::compare(&old.parameters, &new.parameters, &mut changes);
    locks::compare(old, new, &mut changes);
    mappings::compare(&old.mappings, &new.mappings, &mut changes);
    models::compare(&old.models, &new.models, &mut changes);
    types::enums(&old.enums, &new.enums, &mut changes);
    types::flags(&old.flags, &new.flags, &mut changes);
    changes.sort_by(|a, b| (a.impact, &a.subject).cmp(&(b.impact, &b.subject)));
    changes
}

/// The changes as text, grouped by impact, with a closing summary line.
pub fn render(changes: &[Change]) -> String {
    let mut out = String::new();
    for (impact, title) in [
        (Impact::Breaking, "breaking"),
        (Impact::Behaviour, "behaviour"),
        (Impact::Compatible, "compatible"),
    ] {
        let group: Vec<&Change> = changes.iter().filter(|c| c.impact == impact).collect();
        if group.is_empty() {
            continue;
        }
        out += &format!("{title} ({}):\n", group.len());
        for change in group {
            out += &format!("  {}: {}\n", change.subject, change.what);
        }
    }
    let breaking = changes
        .iter()
        .filter(|c| c.impact == Impact::Breaking)
        .count();
    out += &match (changes.len(), breaking) {
        (0, _) => "no changes\n".to_owned(),
        (n, 0) => format!("{n} change(s), none breaking\n"),
        (n, b) => format!("{n} change(s), {b} breaking\n"),
    };
    out
}

/// Items present in only one of two lists, and the pairs present in both, matched by name.
struct Matched<'a, T> {
    removed: Vec<&'a T>,
    added: Vec<&'a T>,
    both: Vec<(&'a T, &'a T)>,
}

fn match_by_name<'a, T>(old: &'a [T], new: &'a [T], name: impl Fn(&T) -> &str) -> Matched<'a, T> {
    let find = |list: &'a [T], wanted: &str| list.iter().find(|item| name(item) == wanted);
    Matched {
        removed: old
            .iter()
            .filter(|o| find(new, name(o)).is_none())
            .collect(),
        added: new
            .iter()
            .filter(|n| find(old, name(n)).is_none())
            .collect(),
        both: old
            .iter()
            .filter_map(|o| Some((o, find(new, name(o))?)))
            .collect(),
    }
}

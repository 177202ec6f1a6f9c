//! PDOs and SRDOs compare alike: a generated struct per mapping, whose fields are its entries,
//! and a communication configuration that only changes what goes on the wire.

use super::{match_by_name, Change, Impact};

/// How one kind of mapping is named and described for the comparison.
pub(super) struct MappingKind<T> {
    /// The subject of each change: ``PDO `tpdo1` ``.
    pub subject: fn(&T) -> String,
    /// The mapping's name, to match old and new.
    pub name: fn(&T) -> &str,
    /// The mapped parameters, in payload order.
    pub entries: fn(&T) -> &[String],
    /// Everything else the drive is configured with, as one comparable text.
    pub configuration: fn(&T) -> String,
    /// What a configuration change means beyond the wire, appended to its message.
    pub consequence: &'static str,
}

/// A removed mapping or changed entries change the generated struct (breaking); an added one is
/// compatible; a changed configuration changes behaviour.
pub(super) fn compare<T>(kind: &MappingKind<T>, old: &[T], new: &[T], out: &mut Vec<Change>) {
    let matched = match_by_name(old, new, kind.name);
    for m in matched.removed {
        out.push(Change::new(Impact::Breaking, (kind.subject)(m), "removed"));
    }
    for m in matched.added {
        out.push(Change::new(Impact::Compatible, (kind.subject)(m), "added"));
    }
    for (o, n) in matched.both {
        let (old_entries, new_entries) = ((kind.entries)(o), (kind.entries)(n));
        if old_entries != new_entries {
            let what = format!(
                "entries {} → {}",
                old_entries.join(", "),
                new_entries.join(", ")
            );
            out.push(Change::new(Impact::Breaking, (kind.subject)(o), what));
        }
        let (before, after) = ((kind.configuration)(o), (kind.configuration)(n));
        if before != after {
            let what = format!("{before} → {after}{}", kind.consequence);
            out.push(Change::new(Impact::Behaviour, (kind.subject)(o), what));
        }
    }
}

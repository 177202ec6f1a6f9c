//! Changes to declared PDO mappings: their structs, fields and wire identity.

use super::{match_by_name, Change, Impact};
use crate::ir::PdoMapping;

/// A removed mapping or changed entries change the generated struct (breaking); a new COB-ID,
/// number or transmission type only changes what goes on the wire.
pub(super) fn compare(old: &[PdoMapping], new: &[PdoMapping], out: &mut Vec<Change>) {
    let matched = match_by_name(old, new, |m| &m.name);
    for m in matched.removed {
        out.push(Change::new(Impact::Breaking, subject(m), "removed"));
    }
    for m in matched.added {
        out.push(Change::new(Impact::Compatible, subject(m), "added"));
    }
    for (o, n) in matched.both {
        if o.entries != n.entries {
            let what = format!(
                "entries {} → {}",
                o.entries.join(", "),
                n.entries.join(", ")
            );
            out.push(Change::new(Impact::Breaking, subject(o), what));
        }
        let wire = |m: &PdoMapping| {
            let cob_id = m.default_cob_id();
            let base = if cob_id.plus_node_id {
                " + node id"
            } else {
                ""
            };
            format!(
                "{:?} {}, COB-ID 0x{:X}{base}, transmission type {:?}, inhibit time {:?}, event timer {:?}",
                m.direction, m.number, cob_id.value, m.transmission_type, m.inhibit_time, m.event_timer
            )
        };
        if wire(o) != wire(n) {
            out.push(Change::new(
                Impact::Behaviour,
                subject(o),
                format!("{} → {}", wire(o), wire(n)),
            ));
        }
    }
}

fn subject(m: &PdoMapping) -> String {
    format!("PDO `{}`", m.name)
}

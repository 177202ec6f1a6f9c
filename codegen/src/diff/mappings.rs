//! Changes to declared PDOs and SRDOs: a generated struct per mapping, whose fields are its
//! entries, and a communication configuration that changes what goes on the wire (and, for an
//! SRDO, the safety signature the drive expects).

use super::{match_by_name, Change, Impact};
use crate::ir::{Mapping, MappingKind, PdoDefaults, SrdoDefaults};

/// A removed mapping or changed entries change the generated struct (breaking); an added one is
/// compatible; a changed configuration changes behaviour. PDOs and SRDOs are matched by name
/// within their kind (they are generated in different modules).
pub(super) fn compare(old: &[Mapping], new: &[Mapping], out: &mut Vec<Change>) {
    for label in ["PDO", "SRDO"] {
        let (old, new) = (of_kind(old, label), of_kind(new, label));
        let matched = match_by_name(&old, &new, |m| &m.name);
        for m in matched.removed {
            out.push(Change::new(Impact::Breaking, subject(m), "removed"));
        }
        for m in matched.added {
            out.push(Change::new(Impact::Compatible, subject(m), "added"));
        }
        for (o, n) in matched.both {
            compare_one(o, n, out);
        }
    }
}

fn of_kind<'a>(list: &'a [Mapping], label: &str) -> Vec<&'a Mapping> {
    list.iter().filter(|m| m.label() == label).collect()
}

fn compare_one(old: &Mapping, new: &Mapping, out: &mut Vec<Change>) {
    if old.entries != new.entries {
        let what = format!(
            "entries {} → {}",
            old.entries.join(", "),
            new.entries.join(", ")
        );
        out.push(Change::new(Impact::Breaking, subject(old), what));
    }
    let (before, after) = (configuration(old), configuration(new));
    if before != after {
        let consequence = match old.kind {
            MappingKind::Pdo(_) => "",
            MappingKind::Srdo(_) => " (the safety signature changes)",
        };
        let what = format!("{before} → {after}{consequence}");
        out.push(Change::new(Impact::Behaviour, subject(old), what));
    }
}

/// ``PDO `tpdo1` ``, ``SRDO `safety_control` ``.
fn subject(m: &Mapping) -> String {
    format!("{} `{}`", m.label(), m.name)
}

/// Everything but the entries that the communication object holds, as one comparable text.
fn configuration(m: &Mapping) -> String {
    match &m.kind {
        MappingKind::Pdo(p) => pdo_wire(m, p),
        MappingKind::Srdo(s) => srdo_configuration(m, s),
    }
}

fn pdo_wire(m: &Mapping, p: &PdoDefaults) -> String {
    let Some(cob_id) = m.default_cob_id() else {
        return String::new();
    };
    let base = if cob_id.plus_node_id {
        " + node id"
    } else {
        ""
    };
    format!(
        "{:?} {}, COB-ID 0x{:X}{base}, transmission type {:?}, inhibit time {:?}, event timer {:?}",
        m.direction, p.number, cob_id.value, m.transmission_type, p.inhibit_time, p.event_timer
    )
}

fn srdo_configuration(m: &Mapping, s: &SrdoDefaults) -> String {
    let [normal, inverted] = s.cob_ids;
    format!(
        "SRDO {} {:?} (direction {}), SCT {} ms, SRVT {} ms, COB-IDs 0x{:X} + {} × node-ID / 0x{:X} + {} × node-ID, transmission type {:?}",
        s.number,
        m.direction,
        m.information_direction(),
        s.sct_ms,
        s.srvt_ms,
        normal.base,
        normal.node_id_factor,
        inverted.base,
        inverted.node_id_factor,
        m.transmission_type
    )
}
#[cfg(test)]
mod tests {
    use crate::diff::{diff, Impact};
    use crate::validate::test_support::device;

    const WORDS: &str = "[[parameter]]\nname = \"w\"\ntype = \"u8\"\ncanopen = { index = 0x6620, subindex = 1 }\nsource = { doc = \"m\", line = 1 }\n[[parameter]]\nname = \"w_inv\"\ntype = \"u8\"\ncanopen = { index = 0x6622, subindex = 1 }\nsource = { doc = \"m\", line = 2 }\n";

    fn srdo(sct: u32, entries: &str) -> String {
        format!("{WORDS}[[srdo]]\nname = \"s\"\nnumber = 1\ndirection = \"rx\"\nsct_ms = {sct}\nsrvt_ms = 20\ncob_ids = [0x101, 0x102]\nentries = {entries}\nsource = {{ doc = \"m\", line = 3 }}\n")
    }

    fn impacts(old: &str, new: &str) -> Vec<Impact> {
        diff(&device(old), &device(new))
            .into_iter()
            .map(|c| c.impact)
            .collect()
    }

    #[test]
    fn srdo_changes_have_their_impact() {
        let base = srdo(50, r#"["w", "w_inv"]"#);
        assert!(impacts(&base, &base).is_empty());
        assert_eq!(
            impacts(&base, &srdo(60, r#"["w", "w_inv"]"#)),
            [Impact::Behaviour]
        );
        assert_eq!(
            impacts(&base, &srdo(50, r#"["w_inv", "w"]"#)),
            [Impact::Breaking]
        );
        assert_eq!(impacts(&base, WORDS), [Impact::Breaking]);
        assert_eq!(impacts(WORDS, &base), [Impact::Compatible]);
    }
}

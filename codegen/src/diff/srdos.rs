//! Changes to declared SRDOs: their structs and their safety configuration.

use super::mappings::{self, MappingKind};
use super::Change;
use crate::ir::SrdoMapping;

/// A removed SRDO or changed entries change the generated struct (breaking); any other change of
/// the configuration changes the wire and the safety signature the drive expects (behaviour).
pub(super) fn compare(old: &[SrdoMapping], new: &[SrdoMapping], out: &mut Vec<Change>) {
    let kind = MappingKind {
        subject: |s: &SrdoMapping| format!("SRDO `{}`", s.name),
        name: |s| &s.name,
        entries: |s| &s.entries,
        configuration,
        consequence: " (the safety signature changes)",
    };
    mappings::compare(&kind, old, new, out);
}

/// Everything but the entries that the communication object holds.
fn configuration(s: &SrdoMapping) -> String {
    let [normal, inverted] = s.cob_ids;
    format!(
        "SRDO {} {:?} (direction {}), SCT {} ms, SRVT {} ms, COB-IDs 0x{:X} + {} × node-ID / 0x{:X} + {} × node-ID, transmission type {:?}",
        s.number,
        s.direction,
        s.information_direction(),
        s.sct_ms,
        s.srvt_ms,
        normal.base,
        normal.node_id_factor,
        inverted.base,
        inverted.node_id_factor,
        s.transmission_type
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

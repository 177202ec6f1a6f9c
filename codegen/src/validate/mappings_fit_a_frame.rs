//! A declared PDO carries at most 64 bits (one classic CAN frame); a declared SRDO maps pairs
//! (normal entry, then an inverted entry of the same width) whose normal data fits one 8-byte
//! frame, the rule of `drivebus::canopen::srdo::mapping`. An oversized mapping is rejected when
//! the code is generated, not when the drive refuses it at run time.

use drivebus_model::canopen::srdo::{mapping::check_mapping, SrdoError};

use crate::diagnostic::Diagnostic;
use crate::ir::{pdo_bits, Device, Mapping, MappingKind};

const RULE: &str = super::rule_name(module_path!());

/// Reports empty PDOs, PDOs over 64 bits and SRDO mappings the runtime would refuse (entries
/// that name nothing are left to `mapping_entries_are_mappable`).
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .mappings
        .iter()
        .filter_map(|m| match m.kind {
            MappingKind::Pdo(_) => pdo_problem(device, m),
            MappingKind::Srdo(_) => srdo_problem(device, m),
        })
        .collect()
}

fn pdo_problem(device: &Device, mapping: &Mapping) -> Option<Diagnostic> {
    let error = |message: String| Diagnostic::error(RULE, mapping.entries_span.clone(), message);
    if mapping.entries.is_empty() {
        let message = format!("PDO `{}` maps nothing", mapping.name);
        return Some(error(message).help("list the parameters it carries in `entries`"));
    }
    let sizes: Vec<(&str, u32)> = mapping
        .entries
        .iter()
        .filter_map(|e| Some((e.as_str(), pdo_bits(device.parameter(e)?.data_type))))
        .collect();
    let total: u32 = sizes.iter().map(|(_, bits)| bits).sum();
    (total > 64).then(|| {
        let parts: Vec<String> = sizes
            .iter()
            .map(|(name, bits)| format!("{name} {bits}"))
            .collect();
        let message = format!(
            "PDO `{}` maps {total} bits; a CAN frame carries 64",
            mapping.name
        );
        error(message).help(format!("{} — split it over two PDOs", parts.join(" + ")))
    })
}

fn srdo_problem(device: &Device, mapping: &Mapping) -> Option<Diagnostic> {
    let objects = mapping.mapped_objects(device)?;
    let Err(SrdoError::BadConfiguration(why)) = check_mapping(&objects) else {
        return None;
    };
    Some(
        Diagnostic::error(
            RULE,
            mapping.entries_span.clone(),
            format!("SRDO `{}`: {why}", mapping.name),
        )
        .help(
            "list the mapping object's entries in sub-index order: normal, inverted, normal, ...",
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    fn pdo(entries: &str) -> String {
        let parameters: String = ["a", "b", "c"]
            .iter()
            .enumerate()
            .map(|(i, name)| format!("[[parameter]]\nname = \"{name}\"\ntype = \"i32\"\ncanopen = {{ index = 0x{:X}, access = \"ro\", pdo = \"tx\" }}\nsource = {{ doc = \"m\", line = 1 }}\n", 0x6064 + i))
            .collect();
        format!("{parameters}\n[[pdo]]\nname = \"p\"\ndirection = \"tx\"\nnumber = 1\ncob_id = 0x181\nentries = {entries}\nsource = {{ doc = \"m\", line = 3 }}\n")
    }

    #[test]
    fn sixty_four_bits_fit() {
        assert!(messages(RULE, &pdo("[\"a\", \"b\"]")).is_empty());
    }

    #[test]
    fn ninety_six_bits_and_nothing_are_reported() {
        assert_eq!(
            messages(RULE, &pdo("[\"a\", \"b\", \"c\"]")),
            ["PDO `p` maps 96 bits; a CAN frame carries 64"]
        );
        assert_eq!(
            messages(RULE, &pdo("[]")),
            ["PDO `p` maps nothing"]
        );
    }

    const WORDS: &str = r#"
[[parameter]]
name = "word"
type = "u8"
canopen = { index = 0x6620, subindex = 1 }
source = { doc = "m", line = 1 }
[[parameter]]
name = "word_inverted"
type = "u8"
canopen = { index = 0x6622, subindex = 1 }
source = { doc = "m", line = 2 }
[[parameter]]
name = "wide_inverted"
type = "u16"
canopen = { index = 0x6622, subindex = 2 }
source = { doc = "m", line = 3 }
"#;

    fn srdo(entries: &str) -> String {
        format!("{WORDS}[[srdo]]\nname = \"s\"\nnumber = 1\ndirection = \"rx\"\nsct_ms = 50\nsrvt_ms = 20\ncob_ids = [0x101, 0x102]\nentries = {entries}\n")
    }

    #[test]
    fn an_srdo_pair_of_equal_widths_is_fine() {
        assert!(messages(
            RULE,
            &srdo(r#"["word", "word_inverted"]"#)
        )
        .is_empty());
    }

    #[test]
    fn odd_srdo_counts_and_unequal_widths_are_reported() {
        assert_eq!(
            messages(RULE, &srdo(r#"["word"]"#)),
            ["SRDO `s`: an SRDO maps pairs of entries: normal data, then its inverted copy"]
        );
        assert_eq!(
            messages(
                RULE,
                &srdo(r#"["word", "wide_inverted"]"#)
            ),
            ["SRDO `s`: an inverted SRDO entry must be as wide as its normal entry"]
        );
    }
}

//! Every declared SRDO maps pairs (normal entry, then an inverted entry of the same width) whose
//! normal data fits one 8-byte frame: the rule of `drivebus::canopen::srdo::mapping`.

use drivebus_model::canopen::srdo::{mapping::check_mapping, SrdoError};

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = "srdo_mappings_pair_and_fit";

/// Reports mappings the runtime would refuse (entries that name nothing are left to
/// `srdo_entries_are_mappable`).
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .srdos
        .iter()
        .filter_map(|s| {
            let objects = s.mapped_objects(device)?;
            let Err(SrdoError::BadConfiguration(why)) = check_mapping(&objects) else {
                return None;
            };
            Some(
                Diagnostic::error(RULE, s.entries_span.clone(), format!("SRDO `{}`: {why}", s.name))
                    .help("list the mapping object's entries in sub-index order: normal, inverted, normal, ..."),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    const PARAMETERS: &str = r#"
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
        format!("{PARAMETERS}[[srdo]]\nname = \"s\"\nnumber = 1\ndirection = \"rx\"\nsct_ms = 50\nsrvt_ms = 20\ncob_ids = [0x101, 0x102]\nentries = {entries}\n")
    }

    #[test]
    fn a_pair_of_equal_widths_is_fine() {
        assert!(messages(
            "srdo_mappings_pair_and_fit",
            &srdo(r#"["word", "word_inverted"]"#)
        )
        .is_empty());
    }

    #[test]
    fn odd_counts_and_unequal_widths_are_reported() {
        assert_eq!(
            messages("srdo_mappings_pair_and_fit", &srdo(r#"["word"]"#)),
            ["SRDO `s`: an SRDO maps pairs of entries: normal data, then its inverted copy"]
        );
        assert_eq!(
            messages(
                "srdo_mappings_pair_and_fit",
                &srdo(r#"["word", "wide_inverted"]"#)
            ),
            ["SRDO `s`: an inverted SRDO entry must be as wide as its normal entry"]
        );
    }
}

//! A declared PDO carries at most 64 bits (one classic CAN frame): an oversized mapping is
//! rejected when the code is generated, not when the drive refuses it at run time.

use crate::diagnostic::Diagnostic;
use crate::ir::{pdo_bits, Device, PdoMapping};

const RULE: &str = "pdo_mappings_fit_eight_bytes";

/// Reports mappings whose entries add up to more than 64 bits, and empty mappings.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .pdos
        .iter()
        .filter_map(|m| problem(device, m))
        .collect()
}

fn problem(device: &Device, mapping: &PdoMapping) -> Option<Diagnostic> {
    if mapping.entries.is_empty() {
        return Some(
            Diagnostic::error(
                RULE,
                mapping.entries_span.clone(),
                format!("PDO `{}` maps nothing", mapping.name),
            )
            .help("list the parameters it carries in `entries`"),
        );
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
        Diagnostic::error(
            RULE,
            mapping.entries_span.clone(),
            format!(
                "PDO `{}` maps {total} bits; a CAN frame carries 64",
                mapping.name
            ),
        )
        .help(format!("{} — split it over two PDOs", parts.join(" + ")))
    })
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    fn mapping(entries: &str) -> String {
        let parameters: String = ["a", "b", "c"]
            .iter()
            .enumerate()
            .map(|(i, name)| format!("[[parameter]]\nname = \"{name}\"\ntype = \"i32\"\ncanopen = {{ index = 0x{:X}, access = \"ro\", pdo = \"tx\" }}\nsource = {{ doc = \"m\", line = 1 }}\n", 0x6064 + i))
            .collect();
        format!("{parameters}\n[[pdo]]\nname = \"p\"\ndirection = \"tx\"\nnumber = 1\ncob_id = 0x181\nentries = {entries}\nsource = {{ doc = \"m\", line = 3 }}\n")
    }

    #[test]
    fn sixty_four_bits_fit() {
        assert!(messages("pdo_mappings_fit_eight_bytes", &mapping("[\"a\", \"b\"]")).is_empty());
    }

    #[test]
    fn ninety_six_bits_and_nothing_are_reported() {
        assert_eq!(
            messages(
                "pdo_mappings_fit_eight_bytes",
                &mapping("[\"a\", \"b\", \"c\"]")
            ),
            ["PDO `p` maps 96 bits; a CAN frame carries 64"]
        );
        assert_eq!(
            messages("pdo_mappings_fit_eight_bytes", &mapping("[]")),
            ["PDO `p` maps nothing"]
        );
    }
}

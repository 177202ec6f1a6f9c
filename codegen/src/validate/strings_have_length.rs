//! `string` and `octets` parameters declare a capacity between 1 and 64 bytes.

use crate::diagnostic::Diagnostic;
use crate::ir::{DataType, Device};

const RULE: &str = super::rule_name(module_path!());

/// Most bytes a value may have (the runtime's fixed buffer).
pub const MAX_TEXT_BYTES: u16 = drivebus_model::MAX_VALUE_BYTES as u16;

/// Reports strings without a usable `length`.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .parameters
        .iter()
        .filter_map(|p| match p.data_type {
            DataType::String(n) | DataType::Octets(n) if n == 0 || n > MAX_TEXT_BYTES => Some(
                Diagnostic::error(
                    RULE,
                    p.spans.data_type.clone(),
                    format!(
                        "`{}` needs a `length` of 1..={MAX_TEXT_BYTES} bytes",
                        p.name
                    ),
                )
                .help("add `length = N` with the capacity the manual gives"),
            ),
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn string_without_length_is_reported() {
        let body = r#"
[[parameter]]
name = "device_name"
type = "string"
canopen = { index = 0x1008, access = "ro" }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["`device_name` needs a `length` of 1..=64 bytes"]
        );
    }
}

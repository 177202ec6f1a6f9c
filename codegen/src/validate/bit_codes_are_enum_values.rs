//! Bits that report error codes (`code` on a bit of a flags type with `codes = "<enum>"`) name
//! an existing enum, and each code is one of its values, so `codes()` of the generated flags
//! type turns every set bit into a documented code (with its `meaning()`).

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

/// Reports an unknown codes enum, codes that are not its values, and codes without an enum.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for f in &device.flags {
        let coded: Vec<_> = f.bits.iter().filter(|b| b.code.is_some()).collect();
        let Some(name) = &f.codes else {
            if let Some(b) = coded.first() {
                out.push(
                    Diagnostic::error(
                        RULE,
                        b.span.clone(),
                        format!("bit `{}` of `{}` has a `code` but the flags type names no `codes` enum", b.name, f.name),
                    )
                    .help("add `codes = \"<enum of the error codes>\"` to the `[[flags]]`"),
                );
            }
            continue;
        };
        let Some(e) = device.enumeration(name) else {
            out.push(Diagnostic::error(
                RULE,
                f.span.clone(),
                format!(
                    "`{}` names the codes enum `{name}`, which does not exist",
                    f.name
                ),
            ));
            continue;
        };
        for b in coded {
            let code = b.code.unwrap_or_default();
            if !e.values.iter().any(|v| v.value == code) {
                out.push(Diagnostic::error(
                    RULE,
                    b.span.clone(),
                    format!(
                        "bit `{}` reports code {code:#06x}, which is not a value of `{name}`",
                        b.name
                    ),
                ));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::{device, messages};

    fn flags(code: &str) -> String {
        format!(
            r#"
[[enum]]
name = "error_code"
type = "u16"
source = {{ doc = "m", line = 1 }}
values = [{{ name = "overvoltage", value = 0x3210, meaning = "Check the supply." }}]

[[flags]]
name = "error_state"
type = "u16"
codes = "error_code"
source = {{ doc = "m", line = 1 }}
bits = [{{ name = "overvoltage", bit = 5, code = {code} }}]

[[parameter]]
name = "errors"
type = "u16"
flags = "error_state"
modbus = {{ table = "holding", address = 1 }}
source = {{ doc = "m", line = 1 }}
"#
        )
    }

    #[test]
    fn a_documented_code_checks_clean() {
        let d = device(&flags("0x3210"));
        assert_eq!(d.flags[0].bits[0].code, Some(0x3210));
    }

    #[test]
    fn an_unknown_code_is_reported() {
        assert_eq!(
            messages(RULE, &flags("0x3211")),
            ["bit `overvoltage` reports code 0x3211, which is not a value of `error_code`"]
        );
    }
}

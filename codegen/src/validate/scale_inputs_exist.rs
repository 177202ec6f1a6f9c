//! A run-time scale reads only integer, unscaled parameters and per-model constants. Where a
//! parameter input is not readable over a protocol the scaled parameter uses (Kinco's encoder
//! resolution has no Modbus register), the user gives its value when opening the handle
//! (`give_<input>`); a read or write before that is a typed `BadScale` error, never an unscaled
//! value.

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Scale};

const RULE: &str = super::rule_name(module_path!());

/// Reports run-time scale inputs that are neither parameters nor constants, or not plain integers.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for p in &device.parameters {
        let (Some(Scale::Runtime { inputs, .. }), Some(span)) = (&p.scale, &p.spans.scale) else {
            continue;
        };
        for name in inputs {
            let error = |message: String| Diagnostic::error(RULE, span.clone(), message);
            if device.is_constant(name) {
                continue;
            }
            let Some(input) = device.parameter(name) else {
                out.push(error(format!(
                    "scale of `{}` reads `{name}`, which is neither a parameter nor a constant",
                    p.name
                )));
                continue;
            };
            if !input.data_type.is_integer()
                || input.scale.is_some()
                || input.enumeration.is_some()
                || input.flags.is_some()
            {
                out.push(error(format!(
                    "scale input `{name}` must be a plain integer parameter without scale"
                )));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    const SPEED: &str = r#"
[[parameter]]
name = "target_speed"
type = "i32"
unit = "rpm"
scale = { expr = "1875 / (512 * encoder_resolution)" }
canopen = { index = 0x60FF, access = "rw" }
modbus = { table = "holding", address = 0x6F00, access = "rw" }
source = { doc = "m", line = 1 }
"#;

    #[test]
    fn unknown_input_is_reported() {
        assert_eq!(
            messages(RULE, SPEED),
            ["scale of `target_speed` reads `encoder_resolution`, which is neither a parameter nor a constant"]
        );
    }

    #[test]
    fn an_input_missing_on_a_protocol_is_given_not_reported() {
        let body = format!("{SPEED}\n[[parameter]]\nname = \"encoder_resolution\"\ntype = \"u32\"\ncanopen = {{ index = 0x6410, subindex = 3, access = \"rw\" }}\nsource = {{ doc = \"m\", line = 1 }}\n");
        let found = crate::validate::test_support::diagnostics(RULE, &body);
        assert!(found.is_empty(), "{found:?}");
    }

    #[test]
    fn a_constant_is_an_input() {
        let body = SPEED.replace("encoder_resolution", "peak_current")
            + "[[constant]]\nname = \"peak_current\"\nsource = { doc = \"m\", line = 1 }\n[[model]]\nname = \"a\"\nconstants = { peak_current = 45 }\nsource = { doc = \"m\", line = 1 }\n";
        assert!(messages(RULE, &body).is_empty());
    }
}

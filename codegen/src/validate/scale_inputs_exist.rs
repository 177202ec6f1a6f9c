//! A run-time scale reads only integer, unscaled parameters. Where an input is not readable over a
//! protocol the scaled parameter uses, the factor cannot be computed there: that is a warning, and
//! the generated API leaves the parameter out of that protocol (it does not compile) rather than
//! return unscaled values.

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Parameter, Scale};

const RULE: &str = "scale_inputs_exist";

/// Whether `p` has a readable Modbus address.
pub fn readable_modbus(p: &Parameter) -> bool {
    p.modbus.iter().any(|a| a.access.read)
}

/// Whether `p` has a readable CANopen address.
pub fn readable_canopen(p: &Parameter) -> bool {
    p.canopen.iter().any(|a| a.access.read)
}

/// Whether `p` has a readable Kinco RS-232 address.
pub fn readable_rs232(p: &Parameter) -> bool {
    p.rs232.iter().any(|a| a.access.read)
}

/// Whether every run-time scale input of `p` is readable by `readable` (true without one).
pub fn inputs_readable(p: &Parameter, device: &Device, readable: fn(&Parameter) -> bool) -> bool {
    match &p.scale {
        Some(Scale::Runtime { inputs, .. }) => inputs
            .iter()
            .all(|i| device.parameter(i).is_some_and(readable)),
        _ => true,
    }
}

/// Reports run-time scale inputs that do not exist or cannot be read.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for p in &device.parameters {
        let (Some(Scale::Runtime { inputs, .. }), Some(span)) = (&p.scale, &p.spans.scale) else {
            continue;
        };
        for name in inputs {
            let error = |message: String| Diagnostic::error(RULE, span.clone(), message);
            let Some(input) = device.parameter(name) else {
                out.push(error(format!(
                    "scale of `{}` reads `{name}`, which is not a parameter",
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
            let missing = [
                ("Modbus", !p.modbus.is_empty() && !readable_modbus(input)),
                ("CANopen", !p.canopen.is_empty() && !readable_canopen(input)),
                ("RS-232", !p.rs232.is_empty() && !readable_rs232(input)),
            ];
            for (protocol, _) in missing.iter().filter(|(_, m)| *m) {
                let message = format!(
                    "scale input `{name}` of `{}` is not readable over {protocol}; `{}` is left out of the {protocol} API",
                    p.name, p.name
                );
                let help =
                    "give the input a readable address on that protocol if the manual has one";
                out.push(error(message).warning().help(help));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
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
            messages("scale_inputs_exist", SPEED),
            ["scale of `target_speed` reads `encoder_resolution`, which is not a parameter"]
        );
    }

    #[test]
    fn input_missing_on_a_protocol_is_reported() {
        let body = format!("{SPEED}\n[[parameter]]\nname = \"encoder_resolution\"\ntype = \"u32\"\ncanopen = {{ index = 0x6410, subindex = 3, access = \"rw\" }}\nsource = {{ doc = \"m\", line = 1 }}\n");
        let found = crate::validate::test_support::diagnostics("scale_inputs_exist", &body);
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].severity, crate::Severity::Warning);
        assert_eq!(
            found[0].message,
            "scale input `encoder_resolution` of `target_speed` is not readable over Modbus; `target_speed` is left out of the Modbus API"
        );
    }
}

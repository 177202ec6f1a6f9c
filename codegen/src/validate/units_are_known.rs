//! Every unit symbol has a newtype in `drivebus::units`.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

/// Reports unknown unit symbols, listing the known ones.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let known: Vec<&str> = drivebus_model::units::ALL.iter().map(|(s, _)| *s).collect();
    device
        .parameters
        .iter()
        .filter_map(|p| {
            let unit = p.unit.as_ref()?;
            let span = p.spans.unit.clone()?;
            drivebus_model::units::type_name(unit).is_none().then(|| {
                Diagnostic::error(
                    RULE,
                    span,
                    format!("unknown unit `{unit}` on `{}`", p.name),
                )
                .help(format!("known units: {}", known.join(", ")))
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn unknown_unit_is_reported() {
        let body = r#"
[[parameter]]
name = "x"
type = "u16"
unit = "furlong"
modbus = { table = "holding", address = 1 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["unknown unit `furlong` on `x`"]
        );
    }
}

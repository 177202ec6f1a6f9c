//! A parameter's value type is one thing: an enum, a flags word, or a scaled number — and an enum
//! or flags type has the parameter's own integer type.

use crate::diagnostic::Diagnostic;
use crate::ir::{DataType, Device, Parameter};

const RULE: &str = super::rule_name(module_path!());

fn conflict(p: &Parameter, message: String, help: &str) -> Diagnostic {
    Diagnostic::error(RULE, p.spans.name.clone(), message).help(help.to_owned())
}

fn type_mismatch(p: &Parameter, kind: &str, name: &str, ty: DataType) -> Option<Diagnostic> {
    (ty != p.data_type).then(|| {
        conflict(
            p,
            format!(
                "`{}` is {} but its {kind} `{name}` is {}",
                p.name,
                p.data_type.name(),
                ty.name()
            ),
            "give the parameter and the type it uses the same integer type",
        )
    })
}

/// Reports parameters whose enum/flags/scale/unit declarations contradict each other.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for p in &device.parameters {
        let typed = p.enumeration.is_some() as u8 + p.flags.is_some() as u8;
        if typed > 1 {
            out.push(conflict(
                p,
                format!("`{}` has both an enum and flags", p.name),
                "choose one value type",
            ));
        }
        if typed > 0 && (p.scale.is_some() || p.unit.is_some()) {
            out.push(conflict(
                p,
                format!(
                    "`{}` is an enum or flags and cannot have a unit or scale",
                    p.name
                ),
                "remove `unit`/`scale`",
            ));
        }
        if (p.scale.is_some() || p.unit.is_some()) && !p.data_type.is_numeric() {
            out.push(conflict(
                p,
                format!(
                    "`{}` is {} and cannot have a unit or scale",
                    p.name,
                    p.data_type.name()
                ),
                "units and scales need a numeric type",
            ));
        }
        if let Some(e) = p.enumeration.as_deref().and_then(|n| device.enumeration(n)) {
            out.extend(type_mismatch(p, "enum", &e.name, e.data_type));
        }
        if let Some(f) = p.flags.as_deref().and_then(|n| device.flags_type(n)) {
            out.extend(type_mismatch(p, "flags", &f.name, f.data_type));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn enum_of_another_width_is_reported() {
        let body = r#"
[[enum]]
name = "mode"
type = "u8"
values = [{ name = "a", value = 1 }]
source = { doc = "m", line = 1 }
[[parameter]]
name = "mode"
type = "u16"
enum = "mode"
modbus = { table = "holding", address = 1 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["`mode` is u16 but its enum `mode` is u8"]
        );
    }
}

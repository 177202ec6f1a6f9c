//! A default fits the type, lies within the range, is one of the allowed values, and is a declared
//! value of the parameter's enum.

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Number};

use super::ranges_fit_type::fits;

/// Reports defaults the parameter itself would refuse.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for p in &device.parameters {
        let (Some(default), Some(span)) = (p.default, &p.spans.default) else {
            continue;
        };
        let mut refuse = |why: String| {
            out.push(Diagnostic::error(
                "defaults_within_range",
                span.clone(),
                format!("default of `{}` {why}", p.name),
            ))
        };
        if !fits(p, default) {
            refuse(format!("does not fit its type {}", p.data_type.name()));
        } else if let Some(r) = p.range.as_ref().filter(|r| !r.contains(default)) {
            refuse(format!(
                "{default} is outside its range {}..={}",
                r.min, r.max
            ));
        }
        if !p.allows(|a| default.compare(a)) {
            refuse(format!("{default} is not one of its allowed values"));
        }
        if let (Some(e), Number::Int(i)) = (
            p.enumeration.as_deref().and_then(|n| device.enumeration(n)),
            default,
        ) {
            if !e.values.iter().any(|v| v.value == i) {
                refuse(format!("{i} is not a value of enum `{}`", e.name));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn default_outside_range_is_reported() {
        let body = r#"
[[parameter]]
name = "address"
type = "u16"
default = 0
range = [1, 247]
modbus = { table = "holding", address = 0x28 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages("defaults_within_range", body),
            ["default of `address` 0 is outside its range 1..=247"]
        );
    }
}

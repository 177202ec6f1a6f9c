//! Enum values fit the enum's integer type and no raw value is listed twice.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

/// Reports enum values outside the type or repeated.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for e in &device.enums {
        let (lo, hi) = e
            .data_type
            .integer_bounds()
            .unwrap_or((i128::MIN, i128::MAX));
        for (i, v) in e.values.iter().enumerate() {
            if !(lo..=hi).contains(&(v.value as i128)) {
                let message = format!(
                    "value {} of `{}` does not fit {}",
                    v.value,
                    e.name,
                    e.data_type.name()
                );
                out.push(Diagnostic::error(RULE, v.span.clone(), message));
            }
            if let Some(first) = e.values[..i].iter().find(|w| w.value == v.value) {
                let message = format!(
                    "`{}` and `{}` of `{}` are both {}",
                    first.name, v.name, e.name, v.value
                );
                out.push(
                    Diagnostic::error(RULE, v.span.clone(), message)
                        .help("an open enum needs one name per value"),
                );
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn out_of_type_and_repeated_values_are_reported() {
        let body = r#"
[[enum]]
name = "mode"
type = "i8"
values = [{ name = "a", value = 200 }, { name = "b", value = 1 }, { name = "c", value = 1 }]
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            [
                "value 200 of `mode` does not fit i8",
                "`b` and `c` of `mode` are both 1"
            ]
        );
    }
}

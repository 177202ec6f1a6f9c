//! A fixed scale has a non-zero factor whose numerator and denominator fit the runtime's `i64`
//! rationals, so the generated `Ratio` constants compile and conversions never divide by zero.

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Scale};

const RULE: &str = super::rule_name(module_path!());

/// Reports zero factors.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .parameters
        .iter()
        .filter_map(|p| match (&p.scale, &p.spans.scale) {
            (Some(Scale::Fixed(scale)), Some(span))
                if scale.factor == drivebus_model::Ratio::ZERO =>
            {
                Some(
                    Diagnostic::error(
                        RULE,
                        span.clone(),
                        format!("scale of `{}` is zero", p.name),
                    )
                    .help("a zero factor would make every value 0 and writes impossible"),
                )
            }
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn zero_factor_is_reported() {
        let body = r#"
[[parameter]]
name = "x"
type = "u16"
scale = "0/5"
modbus = { table = "holding", address = 1 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["scale of `x` is zero"]
        );
    }
}

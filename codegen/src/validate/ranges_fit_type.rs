//! A range has `min <= max`, and ranges and allowed values fit the parameter's type.

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::{Device, Number, Parameter};

const RULE: &str = super::rule_name(module_path!());

/// Whether a raw value fits the parameter's data type. A float type takes finite values its own
/// width can hold (TOML allows `inf` and `nan`, and a value beyond `f32` would be infinite on the
/// wire).
pub fn fits(p: &Parameter, n: Number) -> bool {
    p.fits_type(n)
}

fn out_of_type(p: &Parameter, n: Number, span: &Span) -> Diagnostic {
    Diagnostic::error(
        RULE,
        span.clone(),
        format!("{n} does not fit `{}`, a {}", p.name, p.data_type.name()),
    )
    .help("values here are raw wire values; check the type and the sign")
}

/// Reports inverted ranges and values outside the type.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for p in &device.parameters {
        if let (Some(range), Some(span)) = (&p.range, &p.spans.range) {
            for n in [range.min, range.max].into_iter().filter(|n| !fits(p, *n)) {
                out.push(out_of_type(p, n, span));
            }
            if range.min.compare(range.max) == Some(std::cmp::Ordering::Greater) {
                out.push(Diagnostic::error(
                    RULE,
                    span.clone(),
                    format!("range of `{}` has min above max", p.name),
                ));
            }
        }
        if let Some(span) = &p.spans.allowed {
            for n in p.allowed.iter().filter(|n| !fits(p, **n)) {
                out.push(out_of_type(p, *n, span));
            }
            out.extend(allowed_outside_range(p, span));
        }
    }
    out
}

/// Allowed values the range refuses: no write could ever use them.
fn allowed_outside_range(p: &Parameter, span: &Span) -> Vec<Diagnostic> {
    let Some(r) = &p.range else {
        return Vec::new();
    };
    // Values that do not fit the type are reported already.
    let outside = |n: &&Number| fits(p, **n) && !r.contains(**n);
    let refuse = |n: &Number| {
        let message = format!(
            "allowed value {n} of `{}` is outside its range {}..={}",
            p.name, r.min, r.max
        );
        Diagnostic::error(RULE, span.clone(), message)
            .help("a write of it would be refused; drop the value or widen the range")
    };
    p.allowed.iter().filter(outside).map(refuse).collect()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn negative_bound_on_unsigned_type_is_reported() {
        let body = r#"
[[parameter]]
name = "speed"
type = "u16"
range = [-3000, 3000]
modbus = { table = "holding", address = 1 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["-3000 does not fit `speed`, a u16"]
        );
    }

    #[test]
    fn allowed_values_outside_the_range_are_reported() {
        let body = r#"
[[parameter]]
name = "mode"
type = "u8"
range = [1, 5]
allowed = [1, 7]
modbus = { table = "holding", address = 1 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["allowed value 7 of `mode` is outside its range 1..=5"]
        );
    }

    #[test]
    fn wide_integers_are_compared_exactly() {
        // As floats, 2^63 - 1 and 2^63 - 2 are equal.
        let body = r#"
[[parameter]]
name = "big"
type = "i64"
range = [0, 9223372036854775806]
allowed = [9223372036854775807]
modbus = { table = "holding", address = 1, words = 4 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["allowed value 9223372036854775807 of `big` is outside its range 0..=9223372036854775806"]
        );
    }

    #[test]
    fn float_bounds_must_be_finite_and_within_the_width() {
        let body = r#"
[[parameter]]
name = "gain"
type = "f32"
range = [-1e39, 3.4e38]
allowed = [nan, 1.5]
modbus = { table = "holding", address = 1, words = 2 }
source = { doc = "m", line = 1 }

[[parameter]]
name = "ratio"
type = "f64"
range = [-inf, 1e300]
modbus = { table = "holding", address = 3, words = 4 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            [
                "-1e39 does not fit `gain`, a f32",
                "NaN does not fit `gain`, a f32",
                "-inf does not fit `ratio`, a f64",
            ]
        );
    }
}

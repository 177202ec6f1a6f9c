//! A range has `min <= max`, and ranges and allowed values fit the parameter's type.

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::{Device, Number, Parameter};

const RULE: &str = "ranges_fit_type";

/// Whether a raw value fits the parameter's data type.
pub fn fits(p: &Parameter, n: Number) -> bool {
    match (p.data_type.integer_bounds(), n) {
        (Some((lo, hi)), Number::Int(i)) => (lo..=hi).contains(&(i as i128)),
        (Some(_), Number::Float(_)) => false,
        (None, _) => p.data_type.is_numeric(),
    }
}

fn out_of_type(p: &Parameter, n: Number, span: &Span) -> Diagnostic {
    let value = match n {
        Number::Int(i) => i.to_string(),
        Number::Float(f) => f.to_string(),
    };
    Diagnostic::error(
        RULE,
        span.clone(),
        format!(
            "{value} does not fit `{}`, a {}",
            p.name,
            p.data_type.name()
        ),
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
            if range.min.as_f64() > range.max.as_f64() {
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
        }
    }
    out
}

#[cfg(test)]
mod tests {
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
            messages("ranges_fit_type", body),
            ["-3000 does not fit `speed`, a u16"]
        );
    }
}

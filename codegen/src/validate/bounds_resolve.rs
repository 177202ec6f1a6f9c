//! `bounds = { min, max }` names other parameters that exist wherever the bounded one does, are
//! readable, and carry the same integer type, scale and unit, so their raw values compare with
//! its own.

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Parameter};

const RULE: &str = "bounds_resolve";

/// Reports bounds that are empty, unknown, self-referring, unreadable or of another kind.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for p in &device.parameters {
        let Some(bounds) = &p.bounds else { continue };
        let error = |message: String| Diagnostic::error(RULE, bounds.span.clone(), message);
        if bounds.min.is_none() && bounds.max.is_none() {
            out.push(error(format!(
                "`{}` has `bounds` without `min` or `max`",
                p.name
            )));
        }
        if !p.data_type.is_integer() {
            out.push(error(format!(
                "`{}` is not an integer; bounds compare raw integers",
                p.name
            )));
        }
        out.extend(
            bounds
                .names()
                .filter_map(|name| problem(device, p, name))
                .map(error),
        );
    }
    out
}

/// What is wrong with bound `name` of `p`, if anything.
fn problem(device: &Device, p: &Parameter, name: &str) -> Option<String> {
    let Some(bound) = device.parameter(name) else {
        return Some(format!("bound `{name}` of `{}` is not a parameter", p.name));
    };
    let why = if bound.name == p.name {
        "it is the parameter itself"
    } else if bound.data_type != p.data_type {
        "its type differs"
    } else if format!("{:?}", bound.scale) != format!("{:?}", p.scale) || bound.unit != p.unit {
        "its scale or unit differs"
    } else if !(bound.modbus.iter().any(|a| a.access.read)
        || bound.canopen.iter().any(|a| a.access.read))
    {
        "it is not readable"
    } else if !bound.variants.is_empty()
        && (p.variants.is_empty() || p.variants.iter().any(|v| !bound.variants.contains(v)))
    {
        "it is missing in a variant the parameter exists in"
    } else {
        return None;
    };
    Some(format!(
        "bound `{name}` of `{}` cannot bound it: {why}",
        p.name
    ))
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::{device, messages};

    fn body(bounds: &str, bound_type: &str) -> String {
        format!(
            r#"
[[parameter]]
name = "speed"
type = "u16"
unit = "Hz"
scale = "1/10"
bounds = {bounds}
modbus = {{ table = "holding", address = 40 }}
source = {{ doc = "m", line = 1 }}
[[parameter]]
name = "minimum"
type = "{bound_type}"
unit = "Hz"
scale = "1/10"
modbus = {{ table = "holding", address = 59 }}
source = {{ doc = "m", line = 2 }}
[[parameter]]
name = "maximum"
type = "u16"
unit = "Hz"
scale = "1/10"
modbus = {{ table = "holding", address = 60 }}
source = {{ doc = "m", line = 3 }}
"#
        )
    }

    #[test]
    fn bounds_of_the_same_kind_resolve() {
        let device = device(&body(r#"{ min = "minimum", max = "maximum" }"#, "u16"));
        let bounds = device.parameters[0].bounds.as_ref().unwrap();
        assert_eq!(bounds.names().collect::<Vec<_>>(), ["minimum", "maximum"]);
    }

    #[test]
    fn unknown_self_and_mismatched_bounds_are_reported() {
        assert_eq!(
            messages(
                "bounds_resolve",
                &body(r#"{ min = "minimum", max = "nothing" }"#, "i16")
            ),
            [
                "bound `minimum` of `speed` cannot bound it: its type differs",
                "bound `nothing` of `speed` is not a parameter"
            ]
        );
        assert_eq!(
            messages("bounds_resolve", &body(r#"{ max = "speed" }"#, "u16")),
            ["bound `speed` of `speed` cannot bound it: it is the parameter itself"]
        );
        assert_eq!(
            messages("bounds_resolve", &body("{}", "u16")),
            ["`speed` has `bounds` without `min` or `max`"]
        );
    }
}

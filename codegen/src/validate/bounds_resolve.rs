//! `bounds = { min, max, magnitude }` names other parameters that exist wherever the bounded one
//! does, are readable over every protocol it is written over (each write reads them first), and
//! carry the same scale and unit, so their raw values compare with its own: `min` and `max` the
//! same integer type, `magnitude` any integer type (an unsigned full scale bounds a signed
//! setpoint).

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Parameter};

const RULE: &str = super::rule_name(module_path!());

/// Reports bounds that are empty, unknown, self-referring, unreadable or of another kind.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for p in &device.parameters {
        let Some(bounds) = &p.bounds else { continue };
        let error = |message: String| Diagnostic::error(RULE, bounds.span.clone(), message);
        if bounds.names().next().is_none() {
            out.push(error(format!(
                "`{}` has `bounds` without `min`, `max` or `magnitude`",
                p.name
            )));
        }
        if !p.data_type.is_integer() {
            out.push(error(format!(
                "`{}` is not an integer; bounds compare raw integers",
                p.name
            )));
        }
        let same_type = bounds.min.iter().chain(&bounds.max).map(|n| (n, true));
        let any_integer = bounds.magnitude.iter().map(|n| (n, false));
        out.extend(
            same_type
                .chain(any_integer)
                .filter_map(|(name, same)| problem(device, p, name, same))
                .map(error),
        );
    }
    out
}

/// What is wrong with bound `name` of `p`, if anything.
fn problem(device: &Device, p: &Parameter, name: &str, same_type: bool) -> Option<String> {
    let Some(bound) = device.parameter(name) else {
        return Some(format!("bound `{name}` of `{}` is not a parameter", p.name));
    };
    let why = if bound.name == p.name {
        "it is the parameter itself"
    } else if same_type && bound.data_type != p.data_type {
        "its type differs"
    } else if !bound.data_type.is_integer() {
        "it is not an integer"
    } else if format!("{:?}", bound.scale) != format!("{:?}", p.scale) || bound.unit != p.unit {
        "its scale or unit differs"
    } else if !(bound.modbus.iter().any(|a| a.access.read)
        || bound.canopen.iter().any(|a| a.access.read))
    {
        "it is not readable"
    } else if let Some(protocol) = unread_where_written(p, bound) {
        return Some(format!(
            "bound `{name}` of `{}` cannot bound it: it is not readable over {protocol}, where \
             `{}` is written",
            p.name, p.name
        ));
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

/// A protocol `p` is written over that does not read `bound`: a write there could not check it.
fn unread_where_written(p: &Parameter, bound: &Parameter) -> Option<&'static str> {
    [
        (
            "Modbus",
            p.modbus.iter().any(|a| a.access.write),
            bound.readable_over_modbus(),
        ),
        (
            "CANopen",
            p.canopen.iter().any(|a| a.access.write),
            bound.readable_over_canopen(),
        ),
        (
            "RS-232",
            p.rs232.iter().any(|a| a.access.write),
            bound.readable_over_rs232(),
        ),
    ]
    .into_iter()
    .find(|(_, written, read)| *written && !*read)
    .map(|(protocol, ..)| protocol)
}

#[cfg(test)]
mod tests {
    use super::RULE;
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
    fn a_magnitude_of_another_integer_type_bounds_a_value() {
        let source = body(r#"{ magnitude = "minimum" }"#, "i16");
        assert!(messages(RULE, &source).is_empty());
        let bounds = device(&source).parameters[0].bounds.clone().unwrap();
        assert_eq!(bounds.names().collect::<Vec<_>>(), ["minimum"]);
        assert_eq!(
            messages(RULE, &body(r#"{ min = "minimum" }"#, "i16")),
            ["bound `minimum` of `speed` cannot bound it: its type differs"]
        );
    }

    #[test]
    fn unknown_self_and_mismatched_bounds_are_reported() {
        assert_eq!(
            messages(
                RULE,
                &body(r#"{ min = "minimum", max = "nothing" }"#, "i16")
            ),
            [
                "bound `minimum` of `speed` cannot bound it: its type differs",
                "bound `nothing` of `speed` is not a parameter"
            ]
        );
        assert_eq!(
            messages(RULE, &body(r#"{ max = "speed" }"#, "u16")),
            ["bound `speed` of `speed` cannot bound it: it is the parameter itself"]
        );
        assert_eq!(
            messages(RULE, &body("{}", "u16")),
            ["`speed` has `bounds` without `min`, `max` or `magnitude`"]
        );
    }

    #[test]
    fn a_bound_must_be_readable_over_each_protocol_the_value_is_written_over() {
        let canopen_too = body(r#"{ max = "maximum" }"#, "u16").replace(
            "modbus = { table = \"holding\", address = 40 }",
            "modbus = { table = \"holding\", address = 40 }\ncanopen = { index = 0x2000, subindex = 0 }",
        );
        assert_eq!(
            messages(RULE, &canopen_too),
            ["bound `maximum` of `speed` cannot bound it: it is not readable over CANopen, where \
              `speed` is written"]
        );
    }
}

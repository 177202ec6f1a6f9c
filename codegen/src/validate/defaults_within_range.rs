//! A default fits the type, lies within the range, is one of the allowed values, and is a declared
//! value of the parameter's enum.
//!
//! A node-relative default (`$NODEID+0x180`) is checked on every node ID 1..=127 (not node 0). It
//! must fit the type on each. A vendor EDS often gives such a default absolute limits
//! (`LowLimit=0x181`, `HighLimit=0x18F`) that hold on some node IDs only: that is a warning saying
//! which node IDs the limits allow, not an error (python canopen and other tools load such files).
//! A default no node ID makes acceptable is an error naming the range and the offset.

use drivebus_model::canopen::NodeId;

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::{DefaultCheck, Device, NodeIds, Number, Parameter};

use super::ranges_fit_type::fits;

const RULE: &str = super::rule_name(module_path!());

/// Reports defaults the parameter itself would refuse, and node-relative defaults it accepts on
/// some node IDs only.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for p in &device.parameters {
        let (Some(default), Some(span)) = (p.default, &p.spans.default) else {
            continue;
        };
        match (p.default_plus_node_id, default) {
            (true, Number::Int(offset)) => node_relative(device, p, offset, span, &mut out),
            _ => constant(device, p, default, span, &mut out),
        }
    }
    out
}

/// The checks of a default that is the same on every node.
fn constant(
    device: &Device,
    p: &Parameter,
    default: Number,
    span: &Span,
    out: &mut Vec<Diagnostic>,
) {
    let mut refuse = |why: String| {
        out.push(Diagnostic::error(
            RULE,
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
    if !device.passes(p, DefaultCheck::Allowed, default) {
        refuse(format!("{default} is not one of its allowed values"));
    }
    if !device.passes(p, DefaultCheck::Enum, default) {
        refuse(format!(
            "{default} is not a value of enum `{}`",
            enum_name(p)
        ));
    }
}

/// The checks of `$NODEID+offset`, node ID by node ID: an error where a check refuses it on every
/// node ID (or on a node ID where it does not fit the type), a warning where one narrows the node
/// IDs it is acceptable on.
fn node_relative(
    device: &Device,
    p: &Parameter,
    offset: i64,
    span: &Span,
    out: &mut Vec<Diagnostic>,
) {
    let written = written(offset);
    let values = {
        let (lo, hi) = (
            offset.saturating_add(NodeId::MIN.into()),
            offset.saturating_add(NodeId::MAX.into()),
        );
        format!("{lo}..={hi} on node IDs {}..={}", NodeId::MIN, NodeId::MAX)
    };
    let error = |message: String| {
        Diagnostic::error(
            RULE,
            span.clone(),
            format!("default of `{}` {message}", p.name),
        )
    };
    let passing = |check| {
        device
            .default_node_ids_passing(p, check)
            .unwrap_or(NodeIds::ALL)
    };
    if let Some(id) = passing(DefaultCheck::Type).complement().iter().next() {
        let value = p.default_on(id).unwrap_or(Number::Int(offset));
        out.push(error(format!(
            "for node ID {id}, {value} does not fit its type {}",
            p.data_type.name()
        )));
        return;
    }
    let mut narrowed = Vec::new();
    let mut refused = false;
    let mut acceptable = NodeIds::ALL;
    for check in [
        DefaultCheck::Range,
        DefaultCheck::Allowed,
        DefaultCheck::Enum,
    ] {
        let ids = passing(check);
        acceptable = acceptable.intersection(ids);
        if ids.is_all() {
            continue;
        }
        // What refuses the default, and what allows the node IDs it holds on.
        let (what, who) = match (check, p.range.as_ref()) {
            (DefaultCheck::Range, Some(r)) => (
                format!("is outside its range {}..={}", r.min, r.max),
                "the limits allow",
            ),
            (DefaultCheck::Allowed, _) => (
                "is not one of its allowed values".to_owned(),
                "its allowed values allow",
            ),
            _ => (
                format!("is not a value of enum `{}`", enum_name(p)),
                "its enum allows",
            ),
        };
        if ids.is_empty() {
            refused = true;
            out.push(error(format!(
                "{written} ({values}) {what} on every node ID"
            )));
            continue;
        }
        narrowed.push(format!("{who} node IDs {ids}"));
        let warning = error(format!("{written} {what} on node IDs {}", ids.complement()));
        out.push(
            warning
                .warning()
                .label(format!("{who} node IDs {ids} only"))
                .help(
                    "on any other node ID the drive's own default is a value it refuses; \
                     drivegen keeps the default, and a session opened at such a node ID warns",
                ),
        );
    }
    if acceptable.is_empty() && !refused {
        out.push(error(format!(
            "{written} is acceptable on no node ID: {}",
            narrowed.join(", ")
        )));
    }
}

/// `$NODEID+0x180` as an EDS writes it (a negative offset in decimal).
fn written(offset: i64) -> String {
    match u64::try_from(offset) {
        Ok(o) => format!("$NODEID+0x{o:X}"),
        Err(_) => format!("$NODEID{offset}"),
    }
}

/// The name of the parameter's enum.
fn enum_name(p: &Parameter) -> &str {
    p.enumeration.as_deref().unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::diagnostic::Severity;
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
            messages(RULE, body),
            ["default of `address` 0 is outside its range 1..=247"]
        );
    }

    /// Parameters of `body` given the node-relative default `$NODEID+offset`, checked: each
    /// diagnostic as `(is a warning, message, label)`.
    fn node_relative(body: &str, offset: i64) -> Vec<(bool, String, String)> {
        node_relative_with(body, offset, |_| {})
    }

    /// [`node_relative`], changing the device first (to hold what a TOML description refuses).
    fn node_relative_with(
        body: &str,
        offset: i64,
        change: impl FnOnce(&mut crate::ir::Device),
    ) -> Vec<(bool, String, String)> {
        let mut device = crate::test_support::device(body);
        change(&mut device);
        for p in &mut device.parameters {
            p.default = Some(crate::ir::Number::Int(offset));
            p.default_plus_node_id = true;
            p.spans.default = Some(p.spans.name.clone());
        }
        super::check(&device)
            .into_iter()
            .map(|d| (d.severity == Severity::Warning, d.message, d.label))
            .collect()
    }

    /// A `u32` parameter without a default (the tests give it a node-relative one).
    fn parameter(name: &str, index: u16, extra: &str) -> String {
        format!(
            "[[parameter]]\nname = \"{name}\"\ntype = \"u32\"\n{extra}\ncanopen = {{ index = {index}, subindex = 0, access = \"rw\" }}\nsource = {{ doc = \"m\", line = 1 }}\n"
        )
    }

    #[test]
    fn node_relative_defaults_are_checked_for_every_node_id() {
        // `$NODEID+0x80`, as an EDS writes it: 0x81..=0xFF over node IDs 1..=127.
        let body = parameter("cob_id", 0x2014, "range = [0x81, 0xFF]");
        assert_eq!(node_relative(&body, 0x80), []);
    }

    #[test]
    fn limits_that_hold_on_some_node_ids_are_a_warning_naming_them() {
        // The vendor EDS of #27: `$NODEID+0x180` with `LowLimit=0x181`, `HighLimit=0x18F`.
        let body = parameter("cob_id", 0x1800, "range = [0x181, 0x18F]")
            + &parameter("middle", 0x1801, "range = [0x190, 0x1A0]")
            + &parameter("one", 0x1802, "allowed = [0x185]");
        assert_eq!(
            node_relative(&body, 0x180),
            [
                (
                    true,
                    "default of `cob_id` $NODEID+0x180 is outside its range 385..=399 on node IDs 16..=127".to_owned(),
                    "the limits allow node IDs 1..=15 only".to_owned()
                ),
                (
                    true,
                    "default of `middle` $NODEID+0x180 is outside its range 400..=416 on node IDs 1..=15, 33..=127".to_owned(),
                    "the limits allow node IDs 16..=32 only".to_owned()
                ),
                (
                    true,
                    "default of `one` $NODEID+0x180 is not one of its allowed values on node IDs 1..=4, 6..=127".to_owned(),
                    "its allowed values allow node IDs 5 only".to_owned()
                ),
            ]
        );
    }

    #[test]
    fn a_node_relative_default_no_node_id_makes_acceptable_is_an_error() {
        let body = parameter("cob_id", 0x1800, "range = [0x500, 0x5FF]")
            + &parameter("split", 0x1801, "range = [0x181, 0x18F]");
        // An allowed value outside the range: refused in a TOML description, made here.
        let found = node_relative_with(&body, 0x180, |d| {
            d.parameters[1].allowed = vec![crate::ir::Number::Int(0x1F0)];
        });
        assert_eq!(
            found,
            [
                (
                    false,
                    "default of `cob_id` $NODEID+0x180 (385..=511 on node IDs 1..=127) is outside its range 1280..=1535 on every node ID".to_owned(),
                    String::new()
                ),
                (
                    true,
                    "default of `split` $NODEID+0x180 is outside its range 385..=399 on node IDs 16..=127".to_owned(),
                    "the limits allow node IDs 1..=15 only".to_owned()
                ),
                (
                    true,
                    "default of `split` $NODEID+0x180 is not one of its allowed values on node IDs 1..=111, 113..=127".to_owned(),
                    "its allowed values allow node IDs 112 only".to_owned()
                ),
                (
                    false,
                    "default of `split` $NODEID+0x180 is acceptable on no node ID: the limits allow node IDs 1..=15, its allowed values allow node IDs 112".to_owned(),
                    String::new()
                ),
            ]
        );
    }

    #[test]
    fn a_node_relative_default_beyond_the_type_is_an_error() {
        let mut body = parameter("byte", 0x2000, "");
        body = body.replace("\"u32\"", "\"u8\"");
        assert_eq!(
            node_relative(&body, 0x81),
            [(
                false,
                "default of `byte` for node ID 127, 256 does not fit its type u8".to_owned(),
                String::new()
            )]
        );
    }
}

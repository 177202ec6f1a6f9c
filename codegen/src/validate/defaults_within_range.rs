//! A default fits the type, lies within the range, is one of the allowed values, and is a declared
//! value of the parameter's enum. A node-relative default (`$NODEID+0x80`) must do so for every
//! node ID 1..=127, not for node 0.

use crate::diagnostic::Diagnostic;
use crate::eds::node_id::{FIRST_NODE_ID, LAST_NODE_ID};
use crate::ir::{Device, Number, Parameter};

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
        let values = values_of(p, default);
        if let Some(v) = values.iter().find(|v| !fits(p, v.value)) {
            refuse(format!(
                "{}does not fit its type {}",
                v.prefix(),
                p.data_type.name()
            ));
        } else if let Some(r) = p.range.as_ref() {
            if let Some(v) = values.iter().find(|v| !r.contains(v.value)) {
                refuse(format!(
                    "{}{} is outside its range {}..={}",
                    v.prefix(),
                    v.value,
                    r.min,
                    r.max
                ));
            }
        }
        if let Some(v) = values.iter().find(|v| !p.allows(|a| v.value.compare(a))) {
            refuse(format!(
                "{}{} is not one of its allowed values",
                v.prefix(),
                v.value
            ));
        }
        if let Some(e) = p.enumeration.as_deref().and_then(|n| device.enumeration(n)) {
            let declared = |v: &&Value| match v.value {
                Number::Int(i) => e.values.iter().any(|d| d.value == i),
                Number::Float(_) => true,
            };
            if let Some(v) = values.iter().find(|v| !declared(v)) {
                refuse(format!(
                    "{}{} is not a value of enum `{}`",
                    v.prefix(),
                    v.value,
                    e.name
                ));
            }
        }
    }
    out
}

/// One value a default stands for: on the node `node` when it is node-relative.
struct Value {
    value: Number,
    node: Option<u8>,
}

impl Value {
    /// `"for node ID 5, "` before the reason, for a node-relative default.
    fn prefix(&self) -> String {
        self.node
            .map_or_else(String::new, |id| format!("for node ID {id}, "))
    }
}

/// The default itself, or a node-relative default on every node ID.
fn values_of(p: &Parameter, default: Number) -> Vec<Value> {
    match (p.default_plus_node_id, default) {
        (true, Number::Int(offset)) => (FIRST_NODE_ID..=LAST_NODE_ID)
            .map(|id| Value {
                value: Number::Int(offset.saturating_add(i64::from(id))),
                node: Some(id),
            })
            .collect(),
        _ => vec![Value {
            value: default,
            node: None,
        }],
    }
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

    #[test]
    fn node_relative_defaults_are_checked_for_every_node_id() {
        let body = r#"
[[parameter]]
name = "cob_id"
type = "u32"
default = 0x81
range = [0x81, 0xFF]
canopen = { index = 0x2014, subindex = 0, access = "rw" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "narrow"
type = "u32"
default = 0x81
range = [0x81, 0x90]
canopen = { index = 0x2015, subindex = 0, access = "rw" }
source = { doc = "m", line = 1 }
"#;
        let mut device = crate::test_support::device(body);
        for p in &mut device.parameters {
            // `$NODEID+0x80`, as an EDS writes it: 0x81..=0xFF over node IDs 1..=127.
            p.default = Some(crate::ir::Number::Int(0x80));
            p.default_plus_node_id = true;
        }
        let messages: Vec<String> = super::check(&device)
            .into_iter()
            .map(|d| d.message)
            .collect();
        assert_eq!(
            messages,
            ["default of `narrow` for node ID 17, 145 is outside its range 129..=144"]
        );
    }
}

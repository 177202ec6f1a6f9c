//! No two parameters share a Modbus register (per table) or a CANopen object entry, in any variant
//! both exist in; a read-back (`read_back_of`) shares the register of the parameter it names
//! (`read_backs_share_their_register` checks it is that register).

use super::commands_share_a_register::commands_share_a_register;
use crate::diagnostic::Diagnostic;
use crate::ir::{Device, ModbusAddress, Parameter};

const RULE: &str = super::rule_name(module_path!());

/// Whether two addresses can be active in the same variant.
fn variants_meet(a: &Option<String>, b: &Option<String>, pa: &Parameter, pb: &Parameter) -> bool {
    let active = |v: &Option<String>, p: &Parameter| -> Vec<String> {
        match v {
            Some(v) => vec![v.clone()],
            None => p.variants.clone(),
        }
    };
    let (va, vb) = (active(a, pa), active(b, pb));
    va.is_empty() || vb.is_empty() || va.iter().any(|v| vb.contains(v))
}

/// Whether `a` of `p` or `b` of `q` is declared the read-back of the other parameter.
fn reads_back(p: &Parameter, a: &ModbusAddress, q: &Parameter, b: &ModbusAddress) -> bool {
    a.read_back_of.as_deref() == Some(q.name.as_str())
        || b.read_back_of.as_deref() == Some(p.name.as_str())
}

/// Reports overlapping Modbus register ranges and repeated CANopen entries.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let params = &device.parameters;
    for (i, p) in params.iter().enumerate() {
        for q in &params[..i] {
            for a in &p.modbus {
                let end = a.address as u32 + a.occupies as u32;
                let clash = q.modbus.iter().find(|b| {
                    b.table == a.table
                        && (a.address as u32) < b.address as u32 + b.occupies as u32
                        && (b.address as u32) < end
                        && variants_meet(&a.variant, &b.variant, p, q)
                        && !commands_share_a_register(p, a, q, b)
                        && !reads_back(p, a, q, b)
                });
                if let Some(b) = clash {
                    let message = format!(
                        "{:?} register {:#06x} of `{}` overlaps `{}` at {:#06x}",
                        a.table, a.address, p.name, q.name, b.address
                    )
                    .to_lowercase();
                    out.push(Diagnostic::error(RULE, a.span.clone(), message).help("input and holding registers are separate tables; check the table and the word count"));
                }
            }
            for a in &p.canopen {
                let clash = q.canopen.iter().find(|b| {
                    b.index == a.index
                        && b.subindex == a.subindex
                        && variants_meet(&a.variant, &b.variant, p, q)
                });
                if clash.is_some() {
                    let message = format!(
                        "object {:#06x}:{} of `{}` is also `{}`",
                        a.index, a.subindex, p.name, q.name
                    );
                    out.push(Diagnostic::error(RULE, a.span.clone(), message));
                }
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
    fn overlapping_pair_is_reported_but_tables_are_separate() {
        let body = r#"
[[parameter]]
name = "position"
type = "i32"
modbus = { table = "input", address = 0x6B, words = 2 }
source = { doc = "m", line = 1 }
[[parameter]]
name = "impulses"
type = "u16"
modbus = { table = "input", address = 0x6C }
source = { doc = "m", line = 1 }
[[parameter]]
name = "other"
type = "u16"
modbus = { table = "holding", address = 0x6C }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["input register 0x006c of `impulses` overlaps `position` at 0x006b"]
        );
    }

    #[test]
    fn same_register_in_different_variants_is_fine() {
        let body = r#"
[[variant]]
name = "pc400"
[[variant]]
name = "pc507"
[[parameter]]
name = "a"
type = "u16"
modbus = [{ table = "holding", address = 10, variant = "pc400" }]
source = { doc = "m", line = 1 }
[[parameter]]
name = "b"
type = "u16"
modbus = [{ table = "holding", address = 10, variant = "pc507" }]
source = { doc = "m", line = 1 }
"#;
        assert!(messages(RULE, body).is_empty());
    }
}

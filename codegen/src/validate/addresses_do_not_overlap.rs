//! No two parameters share a Modbus register (per table) or a CANopen object entry, in any variant
//! both exist in; a read-back (`read_back_of`) shares the register of the parameter it names
//! (`read_backs_share_their_register` checks it is that register).

use std::collections::{BTreeSet, HashMap};

use drivebus_model::modbus::Table;

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
    let params = &device.parameters;
    let mut out = Vec::new();
    for (i, j) in sharing_pairs(params) {
        clashes(&params[i], &params[j], &mut out);
    }
    out
}

/// The pairs `(i, j)`, `j < i`, of parameters with a CANopen entry in common or Modbus ranges
/// that meet in a table, in the order a walk over every pair takes them: the reports come in
/// the order of the description, and a description of hundreds of parameters is not checked
/// pair by pair (it was a fifth of loading one, before any frame of `drivegen trace`).
fn sharing_pairs(params: &[Parameter]) -> BTreeSet<(usize, usize)> {
    let mut pairs = BTreeSet::new();
    let mut entries: HashMap<(u16, u8), Vec<usize>> = HashMap::new();
    for (i, p) in params.iter().enumerate() {
        for a in &p.canopen {
            entries.entry((a.index, a.subindex)).or_default().push(i);
        }
    }
    // Each entry's owners in declaration order, so each pairs with those before it.
    for owners in entries.values() {
        for (n, &i) in owners.iter().enumerate() {
            pairs.extend(owners[..n].iter().filter(|&&j| j != i).map(|&j| (i, j)));
        }
    }
    // Ranges by table and start; each meets the ones before it that end past its start.
    let mut ranges: Vec<(Table, u32, u32, usize)> = params
        .iter()
        .enumerate()
        .flat_map(|(i, p)| p.modbus.iter().map(move |a| (i, a)))
        .map(|(i, a)| (a.table, a.address as u32, a.address as u32 + a.occupies as u32, i))
        .collect();
    ranges.sort_unstable();
    for (n, &(table, start, _, i)) in ranges.iter().enumerate() {
        let earlier = ranges[..n].iter().rev();
        let open = earlier.take_while(|r| r.0 == table).filter(|r| r.2 > start);
        pairs.extend(open.filter(|r| r.3 != i).map(|r| (i.max(r.3), i.min(r.3))));
    }
    pairs
}

/// The reports of `p` against `q`, an earlier parameter.
fn clashes(p: &Parameter, q: &Parameter, out: &mut Vec<Diagnostic>) {
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
                "{} register {:#06x} of `{}` overlaps `{}` at {:#06x}",
                a.table.name(),
                a.address,
                p.name,
                q.name,
                b.address
            );
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

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use super::{sharing_pairs, RULE};
    use crate::ir::Parameter;
    use crate::validate::test_support::messages;

    /// Whether two parameters have a CANopen entry in common or Modbus ranges that meet.
    fn share(p: &Parameter, q: &Parameter) -> bool {
        let objects = p.canopen.iter().any(|a| {
            q.canopen
                .iter()
                .any(|b| (a.index, a.subindex) == (b.index, b.subindex))
        });
        let registers = p.modbus.iter().any(|a| {
            q.modbus.iter().any(|b| {
                a.table == b.table
                    && u32::from(a.address) < u32::from(b.address) + u32::from(b.occupies)
                    && u32::from(b.address) < u32::from(a.address) + u32::from(a.occupies)
            })
        });
        objects || registers
    }

    /// The pairs found by sorting and hashing are the pairs a walk over every pair finds, on
    /// the four descriptions (read-backs, commands sharing a register, firmware variants).
    #[test]
    fn the_sharing_pairs_are_every_pair_that_shares() {
        let mut shared = 0;
        for family in ["ezwheel-swd", "kinco-fd", "lafert-smartris", "lenze-smd"] {
            let path = format!("{}/../descriptions/{family}", env!("CARGO_MANIFEST_DIR"));
            let device = crate::check(std::path::Path::new(&path)).device.unwrap();
            let params = &device.parameters;
            let every: BTreeSet<_> = (0..params.len())
                .flat_map(|i| (0..i).map(move |j| (i, j)))
                .filter(|&(i, j)| share(&params[i], &params[j]))
                .collect();
            assert_eq!(sharing_pairs(params), every, "{family}");
            shared += every.len();
        }
        assert!(shared > 10, "{shared}");
    }

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

//! A Modbus address declared `read_back_of = "<parameter>"` is that parameter's register read
//! back: the named parameter exists, has the same type, and is readable at a Modbus address of
//! the same table, register and words; the read-back itself is read-only (writes go to the
//! register's own parameter).

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, ModbusAddress, Parameter};

const RULE: &str = super::rule_name(module_path!());

/// Whether `owner`'s address `b` is the very register `a` reads back, readable.
fn same_register(a: &ModbusAddress, b: &ModbusAddress) -> bool {
    b.table == a.table
        && b.address == a.address
        && b.words == a.words
        && b.word_order == a.word_order
        && b.access.read
}

/// What is wrong with `p`'s read-back address `a` of `owner` (the named parameter, if any).
fn fault(p: &Parameter, a: &ModbusAddress, owner: Option<&Parameter>) -> Option<(String, &'static str)> {
    let name = a.read_back_of.as_deref()?;
    let Some(owner) = owner.filter(|o| o.name != p.name) else {
        return Some((
            format!("`{}` reads back `{name}`, which is not another parameter", p.name),
            "name the parameter whose register this address reads",
        ));
    };
    if a.access.write {
        return Some((
            format!("`{}` reads back `{name}` but is writable there", p.name),
            "a read-back is read-only (`access = \"r\"`): writes go to the register's own parameter",
        ));
    }
    if owner.data_type != p.data_type {
        return Some((
            format!("`{}` reads back `{name}`, a value of another type", p.name),
            "a read-back decodes the register as its owner does: give both the same type",
        ));
    }
    if !owner.modbus.iter().any(|b| same_register(a, b)) {
        let message = format!(
            "`{}` reads back `{name}` at {} register {:#06x}, where `{name}` is not readable",
            p.name,
            a.table.name(),
            a.address
        );
        return Some((message, "give the table, address and words of the owner's own register"));
    }
    None
}

/// Reports read-backs whose register is not their named parameter's, readable.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .parameters
        .iter()
        .flat_map(|p| p.modbus.iter().map(move |a| (p, a)))
        .filter_map(|(p, a)| {
            let owner = a.read_back_of.as_deref().and_then(|n| device.parameter(n));
            let (message, help) = fault(p, a, owner)?;
            Some(Diagnostic::error(RULE, a.span.clone(), message).help(help))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    const OWNER: &str = r#"
[[parameter]]
name = "mode"
type = "i8"
modbus = { table = "holding", address = 0x3500, access = "rw" }
source = { doc = "m", line = 1 }
"#;

    fn display(address: &str) -> String {
        format!(
            "{OWNER}\n[[parameter]]\nname = \"mode_display\"\ntype = \"i8\"\nmodbus = {address}\nsource = {{ doc = \"m\", line = 2 }}\n"
        )
    }

    #[test]
    fn a_read_back_of_the_owners_register_is_fine_and_does_not_overlap() {
        let body = display(r#"{ table = "holding", address = 0x3500, access = "r", read_back_of = "mode" }"#);
        assert!(messages(RULE, &body).is_empty());
        assert!(messages("addresses_do_not_overlap", &body).is_empty());
    }

    #[test]
    fn each_way_a_read_back_misses_its_register_is_reported() {
        let cases = [
            (
                r#"{ table = "holding", address = 0x3500, access = "r", read_back_of = "nothing" }"#,
                "`mode_display` reads back `nothing`, which is not another parameter",
            ),
            (
                r#"{ table = "holding", address = 0x3500, access = "rw", read_back_of = "mode" }"#,
                "`mode_display` reads back `mode` but is writable there",
            ),
            (
                r#"{ table = "holding", address = 0x3501, access = "r", read_back_of = "mode" }"#,
                "`mode_display` reads back `mode` at holding register 0x3501, where `mode` is not readable",
            ),
        ];
        for (address, expected) in cases {
            assert_eq!(messages(RULE, &display(address)), [expected], "{address}");
        }
        let other_type = display(r#"{ table = "holding", address = 0x3500, access = "r", read_back_of = "mode" }"#)
            .replace("name = \"mode_display\"\ntype = \"i8\"", "name = \"mode_display\"\ntype = \"u16\"");
        assert_eq!(
            messages(RULE, &other_type),
            ["`mode_display` reads back `mode`, a value of another type"]
        );
    }

    #[test]
    fn a_register_shared_without_read_back_still_overlaps() {
        let body = display(r#"{ table = "holding", address = 0x3500, access = "r" }"#);
        assert_eq!(
            messages("addresses_do_not_overlap", &body),
            ["holding register 0x3500 of `mode_display` overlaps `mode` at 0x3500"]
        );
    }
}

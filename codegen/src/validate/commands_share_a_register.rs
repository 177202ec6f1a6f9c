//! Several commands on one command register (Lenze smd #1: start, stop, forward, ... one bit per
//! write): write-only command parameters with distinct trigger values may share a register, so
//! `addresses_do_not_overlap` lets them.

use crate::ir::{ModbusAddress, Parameter};

/// Whether `a` of `p` and `b` of `q` are two commands of one command register: the same
/// write-only register span, each parameter a command with its own trigger value.
pub fn commands_share_a_register(
    p: &Parameter,
    a: &ModbusAddress,
    q: &Parameter,
    b: &ModbusAddress,
) -> bool {
    let value = |p: &Parameter| p.command.as_ref().and_then(|c| c.value);
    let write_only = |a: &ModbusAddress| a.access.write && !a.access.read;
    (a.table, a.address, a.words) == (b.table, b.address, b.words)
        && write_only(a)
        && write_only(b)
        && value(p).is_some()
        && value(q).is_some()
        && value(p) != value(q)
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    fn commands(second_value: u16, access: &str) -> String {
        format!(
            r#"
[[parameter]]
name = "stop"
type = "u16"
command = {{ kind = "action", value = 4 }}
modbus = {{ table = "holding", address = 1, access = "w" }}
source = {{ doc = "m", line = 1 }}
[[parameter]]
name = "start"
type = "u16"
command = {{ kind = "action", value = {second_value} }}
modbus = {{ table = "holding", address = 1, access = "{access}" }}
source = {{ doc = "m", line = 2 }}
"#
        )
    }

    #[test]
    fn commands_with_their_own_values_share_a_register() {
        assert!(messages("addresses_do_not_overlap", &commands(8, "w")).is_empty());
    }

    #[test]
    fn the_same_value_or_a_readable_register_still_overlaps() {
        let overlap = ["holding register 0x0001 of `start` overlaps `stop` at 0x0001"];
        assert_eq!(
            messages("addresses_do_not_overlap", &commands(4, "w")),
            overlap
        );
        assert_eq!(
            messages("addresses_do_not_overlap", &commands(8, "rw")),
            overlap
        );
    }
}

//! `[modbus] combined_commands` (several command bits written at once, Lenze smd lines 569-571)
//! names a holding register several command parameters share, and `obeys` is one of them.

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Table};

const RULE: &str = super::rule_name(module_path!());

/// Reports a `combined_commands` whose register holds fewer than two commands or whose `obeys`
/// is not one of them.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let Some(c) = device
        .modbus
        .as_ref()
        .and_then(|m| m.combined_commands.as_ref())
    else {
        return Vec::new();
    };
    let commands: Vec<&str> = device
        .parameters
        .iter()
        .filter(|p| p.command.as_ref().and_then(|c| c.value).is_some())
        .filter(|p| {
            p.modbus
                .iter()
                .any(|a| a.table == Table::Holding && a.address == c.address && a.access.write)
        })
        .map(|p| p.name.as_str())
        .collect();
    let mut found = Vec::new();
    if commands.len() < 2 {
        found.push(
            Diagnostic::error(
                RULE,
                c.span.clone(),
                format!(
                    "holding register {:#06x} is not a register of several commands",
                    c.address
                ),
            )
            .help("name the register that command parameters with their own trigger values share"),
        );
    } else if !commands.contains(&c.obeys.as_str()) {
        found.push(
            Diagnostic::error(
                RULE,
                c.span.clone(),
                format!(
                    "`obeys` names `{}`, which is no command of holding register {:#06x}",
                    c.obeys, c.address
                ),
            )
            .help(format!("one of: {}", commands.join(", "))),
        );
    }
    found
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::{device, messages};

    fn body(address: u16, obeys: &str) -> String {
        format!(
            r#"
[modbus]
combined_commands = {{ address = {address}, obeys = "{obeys}", refusal = 4, source = {{ doc = "m", line = 9 }} }}
[[parameter]]
name = "stop"
type = "u16"
command = {{ kind = "action", value = 4 }}
modbus = {{ table = "holding", address = 1, access = "w" }}
source = {{ doc = "m", line = 1 }}
[[parameter]]
name = "start"
type = "u16"
command = {{ kind = "action", value = 8 }}
modbus = {{ table = "holding", address = 1, access = "w" }}
source = {{ doc = "m", line = 2 }}
"#
        )
    }

    #[test]
    fn a_command_of_the_register_is_accepted() {
        assert!(messages(super::RULE, &body(1, "stop")).is_empty());
        let caps = device(&body(1, "stop")).modbus.unwrap();
        let combined = caps.combined_commands.unwrap();
        assert_eq!(
            (combined.address, combined.obeys.as_str(), combined.refusal),
            (1, "stop", 4)
        );
    }

    #[test]
    fn another_register_or_command_is_refused() {
        assert_eq!(
            messages(super::RULE, &body(2, "stop")),
            ["holding register 0x0002 is not a register of several commands"]
        );
        assert_eq!(
            messages(super::RULE, &body(1, "halt")),
            ["`obeys` names `halt`, which is no command of holding register 0x0001"]
        );
    }
}

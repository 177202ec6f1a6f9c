//! `[modbus] input_reads_holding` (FC 04 reads the holding table, Lenze smd line 237) comes with
//! FC 04 among the device's functions and no parameter in the input table, which FC 04 could then
//! not reach.

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Table};

const RULE: &str = super::rule_name(module_path!());

/// Reports input-table addresses and a missing FC 04 when FC 04 reads the holding table.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let Some(caps) = device.modbus.as_ref().filter(|c| c.input_reads_holding) else {
        return Vec::new();
    };
    let mut found: Vec<Diagnostic> = device
        .parameters
        .iter()
        .flat_map(|p| p.modbus.iter().map(move |a| (p, a)))
        .filter(|(_, a)| a.table == Table::Input)
        .map(|(p, a)| {
            Diagnostic::error(
                RULE,
                a.span.clone(),
                format!(
                    "`{}` is at input register {:#06x}, but `input_reads_holding` makes FC 04 read the holding table",
                    p.name, a.address
                ),
            )
            .help("describe the register in the holding table")
        })
        .collect();
    if !caps.functions.contains(&0x04) {
        if let Some(source) = &caps.source {
            found.push(
                Diagnostic::error(
                    RULE,
                    source.span.clone(),
                    "`input_reads_holding` is set but FC 0x04 is not among the device's functions",
                )
                .help("add 0x04 to `functions`, or drop the key"),
            );
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::{device, messages};

    const REGISTER: &str = r#"
[[parameter]]
name = "speed"
type = "u16"
modbus = { table = "TABLE", address = 24, access = "r" }
source = { doc = "m", line = 2 }
"#;

    fn body(functions: &str, table: &str) -> String {
        format!(
            "[modbus]\nfunctions = [{functions}]\ninput_reads_holding = true\nsource = {{ doc = \"m\", line = 1 }}\n{}",
            REGISTER.replace("TABLE", table)
        )
    }

    #[test]
    fn holding_registers_with_fc_04_are_accepted() {
        assert!(messages(RULE_NAME, &body("3, 4, 6", "holding")).is_empty());
        assert!(
            device(&body("3, 4, 6", "holding"))
                .modbus
                .unwrap()
                .input_reads_holding
        );
    }

    #[test]
    fn an_input_register_or_a_missing_fc_04_is_refused() {
        assert_eq!(
            messages(RULE_NAME, &body("3, 4, 6", "input")),
            ["`speed` is at input register 0x0018, but `input_reads_holding` makes FC 04 read the holding table"]
        );
        assert_eq!(
            messages(RULE_NAME, &body("3, 6", "holding")),
            ["`input_reads_holding` is set but FC 0x04 is not among the device's functions"]
        );
    }

    const RULE_NAME: &str = super::RULE;
}

//! A Modbus address spans enough registers for its type (and at most 32), and input registers are
//! never declared writable.

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Table};

const RULE: &str = super::rule_name(module_path!());

/// Reports register counts that cannot hold the value and writable input registers.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for p in &device.parameters {
        let needed = p.data_type.bytes().div_ceil(2).max(1);
        for a in &p.modbus {
            if a.words < needed || a.words > 32 {
                let message = format!(
                    "`{}` is {} ({} bytes) but its register at {:#06x} spans {} words",
                    p.name,
                    p.data_type.name(),
                    p.data_type.bytes(),
                    a.address,
                    a.words
                );
                out.push(
                    Diagnostic::error(RULE, a.span.clone(), message)
                        .help(format!("use `words = {needed}`")),
                );
            }
            if a.table == Table::Input && a.access.write {
                let message = format!(
                    "input register {:#06x} of `{}` cannot be written",
                    a.address, p.name
                );
                out.push(
                    Diagnostic::error(RULE, a.span.clone(), message)
                        .help("writes go to holding registers (FC 0x06 / 0x10)"),
                );
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
    fn thirty_two_bits_in_one_register_is_reported() {
        let body = r#"
[[parameter]]
name = "position"
type = "i32"
modbus = { table = "input", address = 0x6B, words = 1 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["`position` is i32 (4 bytes) but its register at 0x006b spans 1 words"]
        );
    }
}

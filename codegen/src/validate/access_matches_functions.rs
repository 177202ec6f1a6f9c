//! Every Modbus access a description declares is possible with the function codes the device
//! implements (a holding write needs FC 0x06 or 0x10; reads need 0x03 / 0x04).

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Table};

const RULE: &str = super::rule_name(module_path!());

/// Reports accesses the device's function codes cannot perform.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let Some(caps) = &device.modbus else {
        return Vec::new();
    };
    let has = |fc: u8| caps.functions.contains(&fc);
    let mut out = Vec::new();
    for p in &device.parameters {
        for a in &p.modbus {
            let read_fc = if a.table == Table::Input { 0x04 } else { 0x03 };
            let mut missing = Vec::new();
            if a.access.read && !has(read_fc) {
                missing.push(format!("reading needs FC {read_fc:#04x}"));
            }
            // Without FC 0x10 multi-word values are written word by word with FC 0x06.
            if a.access.write && !has(0x06) && !has(0x10) {
                missing.push("writing needs FC 0x06 or 0x10".to_owned());
            }
            for why in missing {
                let message = format!(
                    "`{}` at {:#06x}: {why}, which the device does not implement",
                    p.name, a.address
                );
                out.push(
                    Diagnostic::error(RULE, a.span.clone(), message)
                        .help("fix the access or `[modbus] functions`"),
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
    fn write_without_write_function_is_reported() {
        let body = r#"
[modbus]
functions = [0x03, 0x04]
[[parameter]]
name = "x"
type = "u16"
modbus = { table = "holding", address = 1, access = "rw" }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["`x` at 0x0001: writing needs FC 0x06 or 0x10, which the device does not implement"]
        );
    }
}

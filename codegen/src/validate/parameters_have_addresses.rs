//! Every parameter can be reached: it has at least one Modbus, CANopen or RS-232 address.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

/// Reports parameters without any address.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .parameters
        .iter()
        .filter(|p| p.modbus.is_empty() && p.canopen.is_empty() && p.rs232.is_empty())
        .map(|p| {
            Diagnostic::error(
                RULE,
                p.spans.name.clone(),
                format!("parameter `{}` has no address", p.name),
            )
            .help("add `modbus = { table, address }`, `canopen = { index, subindex }` or `rs232 = { index, subindex }`")
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn parameter_without_address_is_reported() {
        let body =
            "[[parameter]]\nname = \"x\"\ntype = \"u8\"\nsource = { doc = \"m\", line = 1 }\n";
        assert_eq!(
            messages(RULE, body),
            ["parameter `x` has no address"]
        );
    }
}

//! Every parameter can be reached: it has at least one Modbus, CANopen or RS-232 address.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

/// Reports parameters without any address.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .parameters
        .iter()
        .filter(|p| p.modbus.is_empty() && p.canopen.is_empty() && p.rs232.is_empty())
        .map(|p| {
            Diagnostic::error(
                "parameters_have_addresses",
                p.spans.name.clone(),
                format!("parameter `{}` has no address", p.name),
            )
            .help("add `modbus = { table, address }`, `canopen = { index, subindex }` or `rs232 = { index, subindex }`")
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn parameter_without_address_is_reported() {
        let body =
            "[[parameter]]\nname = \"x\"\ntype = \"u8\"\nsource = { doc = \"m\", line = 1 }\n";
        assert_eq!(
            messages("parameters_have_addresses", body),
            ["parameter `x` has no address"]
        );
    }
}

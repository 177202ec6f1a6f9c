//! A value with a Kinco RS-232 address is 1, 2 or 4 bytes wide: the data protocol has commands
//! for those widths only (manual `003_8cc8f7f4f05b8633.txt`, lines 2245–2251 and 2311–2315).

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

/// Reports RS-232 addresses of values whose width the protocol cannot carry.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .parameters
        .iter()
        .filter(|p| !matches!(p.data_type.bytes(), 1 | 2 | 4))
        .flat_map(|p| {
            p.rs232.iter().map(move |a| {
                let message = format!(
                    "`{}` is {} ({} bytes), but an RS-232 telegram carries 1, 2 or 4 bytes",
                    p.name,
                    p.data_type.name(),
                    p.data_type.bytes()
                );
                Diagnostic::error(RULE, a.span.clone(), message)
                    .help("reach the value over CANopen, or remove its `rs232` address")
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    fn with_type(data_type: &str) -> Vec<String> {
        let body = format!(
            "[[parameter]]\nname = \"x\"\ntype = \"{data_type}\"\nrs232 = {{ index = 0x2000, subindex = 1, access = \"rw\" }}\nsource = {{ doc = \"m\", line = 1 }}\n"
        );
        messages(RULE, &body)
    }

    #[test]
    fn widths_without_a_command_are_reported() {
        assert_eq!(
            with_type("u64"),
            ["`x` is u64 (8 bytes), but an RS-232 telegram carries 1, 2 or 4 bytes"]
        );
        for fits in ["u8", "i16", "u32", "f32"] {
            assert!(with_type(fits).is_empty(), "{fits}");
        }
    }
}

//! A record member's CANopen addresses use the record's index.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

/// Reports members addressed outside their record.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for p in &device.parameters {
        let Some(record) = p
            .record
            .as_deref()
            .and_then(|r| device.records.iter().find(|x| x.name == r))
        else {
            continue;
        };
        if p.canopen.is_empty() {
            let span = p
                .spans
                .record
                .clone()
                .unwrap_or_else(|| p.spans.name.clone());
            out.push(Diagnostic::error(
                RULE,
                span,
                format!("record member `{}` has no CANopen address", p.name),
            ));
        }
        for a in p.canopen.iter().filter(|a| a.index != record.index) {
            let message = format!(
                "`{}` is a member of `{}` ({:#06x}) but is addressed at {:#06x}",
                p.name, record.name, record.index, a.index
            );
            out.push(Diagnostic::error(
                RULE,
                a.span.clone(),
                message,
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn member_outside_its_record_is_reported() {
        let body = r#"
[[record]]
name = "identity"
kind = "record"
index = 0x1018
source = { doc = "m", line = 1 }
[[parameter]]
name = "vendor_id"
type = "u32"
record = "identity"
canopen = { index = 0x1019, subindex = 1, access = "ro" }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["`vendor_id` is a member of `identity` (0x1018) but is addressed at 0x1019"]
        );
    }
}

//! `[identity]` values can be what a drive reports: the covered values of the identity parameter
//! fit its type, the parameter can be read, the revision range is not empty, and each CANopen
//! entry (vendor-ID, product code, revisions) has a readable 1018h object to be checked through.

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, ExpectedIdentity, Parameter};

const RULE: &str = super::rule_name(module_path!());

/// Reports identity values a drive could never report, and entries nothing can read.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let Some(identity) = &device.identity else {
        return Vec::new();
    };
    let mut out = Vec::new();
    if let Some(parameter) = identity
        .parameter
        .as_deref()
        .and_then(|n| device.parameter(n))
    {
        out.extend(values_fit(identity, parameter));
    }
    if let Some((min, max)) = identity.revisions.filter(|(min, max)| min > max) {
        out.push(Diagnostic::error_at_no_place(
            RULE,
            format!("`[identity]` revisions {min:#x}..={max:#x} cover nothing: min is above max"),
        ));
    }
    if device.canopen.is_some() {
        out.extend(unreadable_entries(identity, device));
    }
    out
}

/// The covered values outside the identity parameter's type, and an identity parameter that
/// cannot be read at all.
fn values_fit(identity: &ExpectedIdentity, parameter: &Parameter) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let readable = parameter.readable_over_modbus()
        || parameter.readable_over_canopen()
        || parameter.readable_over_rs232();
    if !readable {
        out.push(
            Diagnostic::error_at_no_place(
                RULE,
                format!(
                    "`[identity]` parameter `{}` cannot be read over any protocol",
                    parameter.name
                ),
            )
            .help("name the register or object that reports the firmware or configuration"),
        );
    }
    let Some((lo, hi)) = parameter.data_type.integer_bounds() else {
        out.push(Diagnostic::error_at_no_place(
            RULE,
            format!(
                "`[identity]` parameter `{}` is {}, not an integer",
                parameter.name,
                parameter.data_type.name()
            ),
        ));
        return out;
    };
    for value in &identity.values {
        if !(lo..=hi).contains(&i128::from(*value)) {
            out.push(Diagnostic::error_at_no_place(
                RULE,
                format!(
                    "`[identity]` value {value} does not fit `{}` ({}): the drive can never report it",
                    parameter.name,
                    parameter.data_type.name()
                ),
            ));
        }
    }
    out
}

/// CANopen entries given without a readable 1018h object to check them through.
fn unreadable_entries(identity: &ExpectedIdentity, device: &Device) -> Vec<Diagnostic> {
    let entries = [
        (1, "vendor_id", identity.vendor_id.is_some()),
        (2, "product_code", identity.product_code.is_some()),
        (3, "revisions", identity.revisions.is_some()),
    ];
    entries
        .into_iter()
        .filter(|(subindex, _, given)| {
            *given
                && !device.parameters.iter().any(|p| {
                    p.canopen
                        .iter()
                        .any(|a| a.index == 0x1018 && a.subindex == *subindex && a.access.read)
                })
        })
        .map(|(subindex, key, _)| {
            Diagnostic::error_at_no_place(
                RULE,
                format!(
                    "`[identity]` gives `{key}` but no readable object 0x1018:{subindex} is described to check it"
                ),
            )
            .warning()
            .help("include the CiA 301 profile or describe the identity object's entry")
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    const FIRMWARE: &str = r#"
[[parameter]]
name = "firmware"
type = "u8"
modbus = { table = "holding", address = 1, access = "r" }
source = { doc = "m", line = 1 }
"#;

    #[test]
    fn values_outside_the_parameter_type_are_reported() {
        let body =
            format!("[identity]\nparameter = \"firmware\"\nvalues = [242, 300, -1]\n{FIRMWARE}");
        assert_eq!(
            messages(RULE, &body),
            [
                "`[identity]` value 300 does not fit `firmware` (u8): the drive can never report it",
                "`[identity]` value -1 does not fit `firmware` (u8): the drive can never report it",
            ]
        );
    }

    #[test]
    fn values_that_fit_pass() {
        let body = format!("[identity]\nparameter = \"firmware\"\nvalues = [0, 255]\n{FIRMWARE}");
        assert!(messages(RULE, &body).is_empty());
    }

    #[test]
    fn an_unreadable_identity_parameter_and_an_empty_revision_range_are_reported() {
        let body = format!(
            "[identity]\nparameter = \"firmware\"\nvalues = [1]\nrevisions = {{ min = 5, max = 2 }}\n{}",
            FIRMWARE.replace("access = \"r\"", "access = \"w\"")
        );
        assert_eq!(
            messages(RULE, &body),
            [
                "`[identity]` parameter `firmware` cannot be read over any protocol",
                "`[identity]` revisions 0x5..=0x2 cover nothing: min is above max",
            ]
        );
    }

    #[test]
    fn a_canopen_entry_without_its_1018h_object_is_a_warning() {
        let body = r#"
[canopen]
source = { doc = "m", line = 1 }

[identity]
vendor_id = 0x515
product_code = 7

[[parameter]]
name = "vendor"
type = "u32"
canopen = { index = 0x1018, subindex = 1, access = "ro" }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["`[identity]` gives `product_code` but no readable object 0x1018:2 is described to check it"]
        );
    }
}

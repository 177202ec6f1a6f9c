//! `[identity]` names a described parameter when it gives values, and gives the values when it
//! names a parameter: a firmware or configuration check needs both.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

/// Reports an identity parameter that does not resolve, or one without values (and vice versa).
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let Some(identity) = &device.identity else {
        return Vec::new();
    };
    let error = |message: String| Diagnostic::error_at_no_place(RULE, message);
    match (&identity.parameter, identity.values.is_empty()) {
        (Some(name), _) if device.parameter(name).is_none() => vec![error(format!(
            "`[identity]` names parameter `{name}`, which is not described"
        ))],
        (Some(name), true) => vec![error(format!(
            "`[identity]` names parameter `{name}` but gives no `values` it covers"
        ))],
        (None, false) => vec![error(
            "`[identity]` gives `values` but no `parameter` to read them from".into(),
        )],
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::{device, messages};

    const FIRMWARE: &str = r#"
[[parameter]]
name = "firmware"
type = "u16"
modbus = { table = "holding", address = 1, access = "r" }
source = { doc = "m", line = 1 }
"#;

    #[test]
    fn unknown_identity_parameter_is_reported() {
        let body = format!("[identity]\nparameter = \"fw\"\nvalues = [1]\n{FIRMWARE}");
        assert_eq!(
            messages(RULE, &body),
            ["`[identity]` names parameter `fw`, which is not described"]
        );
    }

    #[test]
    fn identity_without_values_is_reported() {
        let body = format!("[identity]\nparameter = \"firmware\"\n{FIRMWARE}");
        assert_eq!(
            messages(RULE, &body),
            ["`[identity]` names parameter `firmware` but gives no `values` it covers"]
        );
    }

    #[test]
    fn identity_is_lowered_into_the_ir() {
        let body = format!(
            "[identity]\nvendor_id = 0x515\nrevisions = {{ min = 1, max = 3 }}\nparameter = \"firmware\"\nvalues = [242, 243]\nsource = {{ doc = \"m\", line = 2 }}\n{FIRMWARE}"
        );
        let identity = device(&body).identity.expect("lowered");
        assert_eq!(identity.vendor_id, Some(0x515));
        assert_eq!(identity.product_code, None);
        assert_eq!(identity.revisions, Some((1, 3)));
        assert_eq!(identity.parameter.as_deref(), Some("firmware"));
        assert_eq!(identity.values, [242, 243]);
    }
}

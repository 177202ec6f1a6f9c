//! A description with a `[canopen]` section describes the objects every CANopen device has
//! (CiA 301 §7.5.2): device type (1000h), error register (1001h) and the identity object (1018h,
//! at least its sub-index 0 and the vendor-ID, sub-index 1). Masters read them first (python
//! canopen, lely, CiA 302 boot-up); the exported EDS lists them under `[MandatoryObjects]`. Include
//! them from `profiles/cia301.toml` unless the manual gives them. A device read from a vendor EDS
//! (or an overlay of one) is not checked: the EDS is the vendor's own object list, and its
//! objects are imported as they are.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;
use crate::mandatory_objects::MANDATORY_OBJECTS;

const RULE: &str = super::rule_name(module_path!());

/// Reports each mandatory object a CANopen description leaves out.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let from_eds = device
        .sources
        .iter()
        .any(|s| s.id == crate::eds::EDS_SOURCE_ID);
    if device.canopen.is_none() || from_eds {
        return Vec::new();
    }
    MANDATORY_OBJECTS
        .iter()
        .filter(|(index, subindex, _)| !describes(device, *index, *subindex))
        .map(|(index, subindex, name)| {
            Diagnostic::error_at_no_place(
                RULE,
                format!(
                    "a CANopen device must describe the mandatory object {index:04X}h sub {subindex}"
                ),
            )
            .help(format!(
                "include `{name}` from `profiles/cia301.toml` (and its record or flags), or describe it from the manual"
            ))
        })
        .collect()
}

fn describes(device: &Device, index: u16, subindex: u8) -> bool {
    device
        .parameters
        .iter()
        .flat_map(|p| &p.canopen)
        .any(|a| a.index == index && a.subindex == subindex)
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    const CANOPEN: &str = r#"
[canopen]
default_node_id = 1
source = { doc = "m", line = 1 }
"#;

    fn parameter(name: &str, index: u16, subindex: u8) -> String {
        format!(
            r#"
[[parameter]]
name = "{name}"
type = "u32"
canopen = {{ index = {index}, subindex = {subindex}, access = "ro" }}
source = {{ doc = "m", line = 1 }}
"#
        )
    }

    #[test]
    fn canopen_description_without_identity_is_reported() {
        let body = format!(
            "{CANOPEN}{}{}",
            parameter("device_type", 0x1000, 0),
            parameter("error_register", 0x1001, 0)
        );
        assert_eq!(
            messages(RULE, &body),
            [
                "a CANopen device must describe the mandatory object 1018h sub 0",
                "a CANopen device must describe the mandatory object 1018h sub 1",
            ]
        );
    }

    #[test]
    fn canopen_description_with_every_mandatory_object_passes() {
        let body = format!(
            "{CANOPEN}{}{}{}{}",
            parameter("device_type", 0x1000, 0),
            parameter("error_register", 0x1001, 0),
            parameter("identity_count", 0x1018, 0),
            parameter("vendor_id", 0x1018, 1)
        );
        assert!(messages(RULE, &body).is_empty());
    }

    #[test]
    fn description_without_canopen_section_is_not_checked() {
        assert!(messages(RULE, &parameter("x", 0x2000, 0)).is_empty());
    }
}

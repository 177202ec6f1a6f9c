//! Every entry of a declared PDO names a parameter with a CANopen object valid in every variant,
//! of a fixed-size type, whose description allows mapping it in the PDO's direction.

use crate::diagnostic::Diagnostic;
use crate::ir::{DataType, Device, Pdo, PdoDirection, PdoMapping};

const RULE: &str = "pdo_entries_are_mappable";

/// Reports entries that name nothing, have no CANopen object, are strings, or may not be mapped.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .pdos
        .iter()
        .flat_map(|m| m.entries.iter().filter_map(move |e| problem(device, m, e)))
        .collect()
}

fn problem(device: &Device, mapping: &PdoMapping, entry: &str) -> Option<Diagnostic> {
    let error = |message: String, help: &str| {
        Some(Diagnostic::error(RULE, mapping.entries_span.clone(), message).help(help))
    };
    let Some(p) = device.parameter(entry) else {
        return error(
            format!(
                "PDO `{}` maps `{entry}`, which is not a parameter",
                mapping.name
            ),
            "entries are parameter names",
        );
    };
    let Some(object) = p.pdo_object() else {
        return error(
            format!(
                "`{entry}` in PDO `{}` has no CANopen object valid in every variant",
                mapping.name
            ),
            "give the parameter a `canopen` address without `variant`",
        );
    };
    if matches!(p.data_type, DataType::String(_) | DataType::Octets(_)) {
        return error(
            format!(
                "`{entry}` in PDO `{}` is a {}, which PDOs do not carry",
                mapping.name,
                p.data_type.name()
            ),
            "map numbers, booleans and bit words",
        );
    }
    let allowed = match mapping.direction {
        PdoDirection::Tx => matches!(object.pdo, Pdo::Tx | Pdo::Both),
        PdoDirection::Rx => matches!(object.pdo, Pdo::Rx | Pdo::Both),
    };
    if allowed {
        return None;
    }
    let (way, key) = match mapping.direction {
        PdoDirection::Tx => ("a transmit", "tx"),
        PdoDirection::Rx => ("a receive", "rx"),
    };
    error(
        format!(
            "`{entry}` may not be mapped into {way} PDO (`{}`)",
            mapping.name
        ),
        &format!(
            "its `canopen` address needs `pdo = \"{key}\"` or `\"both\"` if the manual allows it"
        ),
    )
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    const PARAMETERS: &str = r#"
[[parameter]]
name = "statusword"
type = "u16"
canopen = { index = 0x6041, access = "ro", pdo = "tx" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "name"
type = "string"
length = 8
canopen = { index = 0x1008, access = "ro" }
source = { doc = "m", line = 2 }
"#;

    fn mapping(direction: &str, entries: &str) -> String {
        format!("{PARAMETERS}\n[[pdo]]\nname = \"p\"\ndirection = \"{direction}\"\nnumber = 1\ncob_id = \"$NODEID+0x180\"\nentries = {entries}\nsource = {{ doc = \"m\", line = 3 }}\n")
    }

    #[test]
    fn a_transmit_object_maps_into_a_tpdo() {
        assert!(messages(
            "pdo_entries_are_mappable",
            &mapping("tx", "[\"statusword\"]")
        )
        .is_empty());
    }

    #[test]
    fn unknown_names_strings_and_wrong_directions_are_reported() {
        assert_eq!(
            messages(
                "pdo_entries_are_mappable",
                &mapping("rx", "[\"statusword\", \"name\", \"speed\"]")
            ),
            [
                "`statusword` may not be mapped into a receive PDO (`p`)",
                "`name` in PDO `p` is a string, which PDOs do not carry",
                "PDO `p` maps `speed`, which is not a parameter",
            ]
        );
    }
}

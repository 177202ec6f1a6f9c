//! Every entry of a declared PDO or SRDO names a parameter with a CANopen object valid in every
//! variant, of a fixed-size type; a PDO's entries also allow mapping in the PDO's direction.

use crate::diagnostic::Diagnostic;
use crate::ir::{DataType, Device, Direction, Mapping, MappingKind, Parameter, Pdo};

const RULE: &str = super::rule_name(module_path!());

/// Reports entries that name nothing, have no CANopen object, are strings, or may not be mapped.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .mappings
        .iter()
        .flat_map(|m| m.entries.iter().filter_map(move |e| problem(device, m, e)))
        .collect()
}

fn problem(device: &Device, mapping: &Mapping, entry: &str) -> Option<Diagnostic> {
    let error = |message: String, help: &str| {
        Some(Diagnostic::error(RULE, mapping.entries_span.clone(), message).help(help))
    };
    let (label, name) = (mapping.label(), &mapping.name);
    let Some(p) = device.parameter(entry) else {
        let help = match mapping.kind {
            MappingKind::Pdo(_) => "entries are parameter names",
            MappingKind::Srdo(_) => {
                "entries are parameter names, normal then inverted, as the mapping object lists them"
            }
        };
        return error(
            format!("{label} `{name}` maps `{entry}`, which is not a parameter"),
            help,
        );
    };
    if p.pdo_object().is_none() {
        return error(
            format!("`{entry}` in {label} `{name}` has no CANopen object valid in every variant"),
            "give the parameter a `canopen` address without `variant`",
        );
    }
    if matches!(p.data_type, DataType::String(_) | DataType::Octets(_)) {
        return error(
            format!(
                "`{entry}` in {label} `{name}` is a {}, which {label}s do not carry",
                p.data_type.name()
            ),
            "map numbers, booleans and bit words",
        );
    }
    match mapping.kind {
        MappingKind::Pdo(_) => wrong_direction(mapping, p, entry),
        // The safety objects an SRDO maps say nothing of PDOs.
        MappingKind::Srdo(_) => None,
    }
}

/// A PDO entry whose object the description does not allow in the PDO's direction.
fn wrong_direction(mapping: &Mapping, p: &Parameter, entry: &str) -> Option<Diagnostic> {
    let object = p.pdo_object()?;
    let (allowed, way, key) = match mapping.direction {
        Direction::Tx => (
            matches!(object.pdo, Pdo::Tx | Pdo::Both),
            "a transmit",
            "tx",
        ),
        Direction::Rx => (matches!(object.pdo, Pdo::Rx | Pdo::Both), "a receive", "rx"),
    };
    (!allowed).then(|| {
        Diagnostic::error(
            RULE,
            mapping.entries_span.clone(),
            format!(
                "`{entry}` may not be mapped into {way} PDO (`{}`)",
                mapping.name
            ),
        )
        .help(format!(
            "its `canopen` address needs `pdo = \"{key}\"` or `\"both\"` if the manual allows it"
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::RULE;
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

    fn pdo(direction: &str, entries: &str) -> String {
        format!("{PARAMETERS}\n[[pdo]]\nname = \"p\"\ndirection = \"{direction}\"\nnumber = 1\ncob_id = \"$NODEID+0x180\"\nentries = {entries}\nsource = {{ doc = \"m\", line = 3 }}\n")
    }

    #[test]
    fn a_transmit_object_maps_into_a_tpdo() {
        assert!(messages(
            RULE,
            &pdo("tx", "[\"statusword\"]")
        )
        .is_empty());
    }

    #[test]
    fn unknown_names_strings_and_wrong_directions_are_reported() {
        assert_eq!(
            messages(
                RULE,
                &pdo("rx", "[\"statusword\", \"name\", \"speed\"]")
            ),
            [
                "`statusword` may not be mapped into a receive PDO (`p`)",
                "`name` in PDO `p` is a string, which PDOs do not carry",
                "PDO `p` maps `speed`, which is not a parameter",
            ]
        );
    }

    #[test]
    fn srdo_entries_need_no_pdo_direction_but_a_number() {
        let srdo = format!("{PARAMETERS}[[srdo]]\nname = \"bad\"\nnumber = 1\ndirection = \"rx\"\nsct_ms = 50\nsrvt_ms = 20\ncob_ids = [0x101, 0x102]\nentries = [\"statusword\", \"name\", \"nothing\"]\n");
        assert_eq!(
            messages(RULE, &srdo),
            [
                "`name` in SRDO `bad` is a string, which SRDOs do not carry",
                "SRDO `bad` maps `nothing`, which is not a parameter",
            ]
        );
    }
}

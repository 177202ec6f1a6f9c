//! Every entry of a declared SRDO names a parameter with a CANopen object valid in every variant,
//! of a fixed-size numeric or boolean type.

use crate::diagnostic::Diagnostic;
use crate::ir::{DataType, Device, SrdoMapping};

const RULE: &str = "srdo_entries_are_mappable";

/// Reports entries that name nothing, have no CANopen object, or are strings.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .srdos
        .iter()
        .flat_map(|s| s.entries.iter().filter_map(move |e| problem(device, s, e)))
        .collect()
}

fn problem(device: &Device, srdo: &SrdoMapping, entry: &str) -> Option<Diagnostic> {
    let error = |message: String, help: &str| {
        Some(Diagnostic::error(RULE, srdo.entries_span.clone(), message).help(help))
    };
    let Some(p) = device.parameter(entry) else {
        return error(
            format!(
                "SRDO `{}` maps `{entry}`, which is not a parameter",
                srdo.name
            ),
            "entries are parameter names, normal then inverted, as the mapping object lists them",
        );
    };
    if p.pdo_object().is_none() {
        return error(
            format!(
                "`{entry}` in SRDO `{}` has no CANopen object valid in every variant",
                srdo.name
            ),
            "give the parameter a `canopen` address without `variant`",
        );
    }
    if matches!(p.data_type, DataType::String(_) | DataType::Octets(_)) {
        return error(
            format!(
                "`{entry}` in SRDO `{}` is a {}, which SRDOs do not carry",
                srdo.name,
                p.data_type.name()
            ),
            "map numbers, booleans and bit words",
        );
    }
    None
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    #[test]
    fn unknown_and_string_entries_are_reported() {
        let body = r#"
[[parameter]]
name = "label"
type = "string"
length = 4
canopen = { index = 0x2000 }
source = { doc = "m", line = 1 }
[[srdo]]
name = "bad"
number = 1
direction = "rx"
sct_ms = 50
srvt_ms = 20
cob_ids = [0x101, 0x102]
entries = ["label", "nothing"]
"#;
        assert_eq!(
            messages("srdo_entries_are_mappable", body),
            [
                "`label` in SRDO `bad` is a string, which SRDOs do not carry",
                "SRDO `bad` maps `nothing`, which is not a parameter",
            ]
        );
    }
}

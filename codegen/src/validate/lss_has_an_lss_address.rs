//! A description that says the device is an LSS slave (`[canopen] lss`, CiA 305) cites the
//! manual's statement, and describes the LSS address: the identity object 1018h sub 1-4
//! (vendor-ID, product code, revision number, serial number). A master selects the node by those
//! four words and Fastscan finds it by them; the simulator answers them. Include them from
//! `profiles/cia301.toml`. A device read from a vendor EDS (`LSS_Supported=1`) is not checked:
//! the EDS is the citation, and its objects are the vendor's.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

/// The identity entries that make the LSS address, with the profile names that describe them.
const ADDRESS: [(u8, &str); 4] = [
    (1, "vendor_id"),
    (2, "product_code"),
    (3, "revision_number"),
    (4, "serial_number"),
];

/// Reports an uncited `lss` and each word of the LSS address the description leaves out.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let from_eds = device
        .sources
        .iter()
        .any(|s| s.id == crate::eds::EDS_SOURCE_ID);
    let Some(lss) = device.canopen.as_ref().and_then(|c| c.lss.as_ref()) else {
        return Vec::new();
    };
    if from_eds {
        return Vec::new();
    }
    let mut found = Vec::new();
    if lss.source.is_none() {
        found.push(
            Diagnostic::error(RULE, lss.span.clone(), "`lss` does not cite the manual")
                .help("add `source = { doc = \"...\", line = N }` naming where the manual says the drive supports LSS"),
        );
    }
    for (subindex, name) in ADDRESS {
        if !describes(device, subindex) {
            found.push(
                Diagnostic::error(
                    RULE,
                    lss.span.clone(),
                    format!(
                        "an LSS slave needs its LSS address: 1018h sub {subindex} is not described"
                    ),
                )
                .help(format!("include `{name}` from `profiles/cia301.toml`")),
            );
        }
    }
    found
}

fn describes(device: &Device, subindex: u8) -> bool {
    device
        .parameters
        .iter()
        .flat_map(|p| &p.canopen)
        .any(|a| a.index == 0x1018 && a.subindex == subindex)
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    fn identity(subs: &[u8]) -> String {
        subs.iter()
            .map(|sub| {
                format!(
                    r#"
[[parameter]]
name = "identity_{sub}"
type = "u32"
canopen = {{ index = 0x1018, subindex = {sub}, access = "ro" }}
source = {{ doc = "m", line = 1 }}
"#
                )
            })
            .collect()
    }

    #[test]
    fn an_lss_slave_without_serial_number_or_citation_is_reported() {
        let body = format!(
            "[canopen]\nlss = {{}}\nsource = {{ doc = \"m\", line = 1 }}\n{}",
            identity(&[0, 1, 2, 3])
        );
        assert_eq!(
            messages("lss_has_an_lss_address", &body),
            [
                "`lss` does not cite the manual",
                "an LSS slave needs its LSS address: 1018h sub 4 is not described",
            ]
        );
    }

    #[test]
    fn a_cited_lss_slave_with_its_address_passes() {
        let body = format!(
            "[canopen]\nlss = {{ source = {{ doc = \"m\", line = 2 }} }}\n{}",
            identity(&[0, 1, 2, 3, 4])
        );
        assert!(messages("lss_has_an_lss_address", &body).is_empty());
    }

    #[test]
    fn a_device_without_lss_is_not_checked() {
        let body = format!("[canopen]\ndefault_node_id = 1\n{}", identity(&[0, 1]));
        assert!(messages("lss_has_an_lss_address", &body).is_empty());
    }
}

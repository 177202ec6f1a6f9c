//! What a connected drive must report before a driver trusts it: the `[identity]` as a list of
//! parameters to read and the raw values each may hold. The CANopen entries (vendor-ID, product
//! code, revision range) are checked through the parameters at 1018h sub 1-3, the firmware or
//! configuration entry through its own parameter. The generated `verify_identity` and
//! `drivegen write` read the same list.

use serde::Serialize;

use super::{Device, Parameter};

/// The raw values an identity parameter may hold (JSON: a list, or `{ "min", "max" }`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(untagged)]
pub enum Covered {
    /// One of these values.
    Values(Vec<i64>),
    /// A value within `min..=max`.
    Range {
        /// Smallest covered value.
        min: i64,
        /// Largest covered value.
        max: i64,
    },
}

impl Covered {
    /// Whether `raw` is covered.
    pub fn contains(&self, raw: i128) -> bool {
        match self {
            Covered::Values(values) => values.iter().any(|v| i128::from(*v) == raw),
            Covered::Range { min, max } => (i128::from(*min)..=i128::from(*max)).contains(&raw),
        }
    }
}

impl std::fmt::Display for Covered {
    /// `[400, 507]` or `0x2..=0x4`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Covered::Values(values) => write!(f, "{values:?}"),
            Covered::Range { min, max } => write!(f, "{min:#x}..={max:#x}"),
        }
    }
}

/// One identity parameter and the values the description covers.
#[derive(Debug, Clone)]
pub struct IdentityCheck<'a> {
    /// The parameter to read.
    pub parameter: &'a Parameter,
    /// The raw values it may hold.
    pub covered: Covered,
}

/// CiA 301 identity object.
const IDENTITY_OBJECT: u16 = 0x1018;

impl Device {
    /// The identity checks of `[identity]`, in order: the firmware / configuration parameter,
    /// then vendor-ID, product code and revision number (1018h sub 1-3) where the description
    /// gives them and describes the object. Entries the manual does not give are not checked.
    pub fn identity_checks(&self) -> Vec<IdentityCheck<'_>> {
        let Some(identity) = &self.identity else {
            return Vec::new();
        };
        let by_name = identity
            .parameter
            .as_deref()
            .and_then(|name| self.parameter(name))
            .map(|parameter| IdentityCheck {
                parameter,
                covered: Covered::Values(identity.values.clone()),
            });
        let canopen = [
            (
                1,
                identity.vendor_id.map(|v| Covered::Values(vec![v.into()])),
            ),
            (
                2,
                identity
                    .product_code
                    .map(|v| Covered::Values(vec![v.into()])),
            ),
            (
                3,
                identity.revisions.map(|(min, max)| Covered::Range {
                    min: min.into(),
                    max: max.into(),
                }),
            ),
        ];
        let by_object = canopen.into_iter().filter_map(|(subindex, covered)| {
            Some(IdentityCheck {
                parameter: self.identity_entry(subindex)?,
                covered: covered?,
            })
        });
        by_name.into_iter().chain(by_object).collect()
    }

    /// The readable parameter at 1018h `subindex`.
    fn identity_entry(&self, subindex: u8) -> Option<&Parameter> {
        self.parameters.iter().find(|p| {
            p.canopen
                .iter()
                .any(|a| a.index == IDENTITY_OBJECT && a.subindex == subindex && a.access.read)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::device;

    const OBJECTS: &str = r#"
[[parameter]]
name = "vendor"
type = "u32"
canopen = { index = 0x1018, subindex = 1, access = "ro" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "revision"
type = "u32"
canopen = { index = 0x1018, subindex = 3, access = "ro" }
source = { doc = "m", line = 1 }
"#;

    #[test]
    fn canopen_entries_are_checked_through_the_described_1018h_parameters() {
        let body = format!(
            "[identity]\nvendor_id = 0x515\nproduct_code = 7\nrevisions = {{ min = 2, max = 4 }}\n{OBJECTS}"
        );
        let device = device(&body);
        let checks: Vec<(&str, Covered)> = device
            .identity_checks()
            .into_iter()
            .map(|c| (c.parameter.name.as_str(), c.covered))
            .collect();
        // No parameter at 1018h sub 2: the product code cannot be read, so it is not checked.
        assert_eq!(
            checks,
            [
                ("vendor", Covered::Values(vec![0x515])),
                ("revision", Covered::Range { min: 2, max: 4 }),
            ]
        );
    }

    #[test]
    fn ranges_and_lists_cover_their_values_only() {
        let range = Covered::Range { min: 2, max: 4 };
        assert!(range.contains(4) && !range.contains(5) && !range.contains(1));
        assert_eq!(range.to_string(), "0x2..=0x4");
        let values = Covered::Values(vec![400, 507]);
        assert!(values.contains(507) && !values.contains(401));
        assert_eq!(values.to_string(), "[400, 507]");
    }
}

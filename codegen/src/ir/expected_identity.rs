//! The identity a description was written for (`[identity]`): what a connected drive must report
//! before a driver trusts addresses and scales with it.

use serde::Serialize;

use super::Citation;

/// The drive, firmware and configuration the description covers. A field left out is unknown
/// (the manual does not give it) and is not checked.
#[derive(Debug, Clone, Serialize)]
pub struct ExpectedIdentity {
    /// CANopen vendor-ID (1018h sub 1).
    pub vendor_id: Option<u32>,
    /// CANopen product code (1018h sub 2).
    pub product_code: Option<u32>,
    /// Inclusive range of CANopen revision numbers (1018h sub 3) covered.
    pub revisions: Option<(u32, u32)>,
    /// Parameter whose value tells the firmware or parameter configuration (for example a Modbus
    /// firmware-release register).
    pub parameter: Option<String>,
    /// Values of `parameter` the description covers.
    pub values: Vec<i64>,
    /// Citation.
    pub source: Option<Citation>,
}

impl ExpectedIdentity {
    /// Whether the description covers a CANopen node reporting these 1018h entries (`None`: the
    /// node did not answer that entry): the vendor-ID must be known and equal; product code and
    /// revision are compared where the description gives them.
    pub fn covers_node(
        &self,
        vendor_id: Option<u32>,
        product_code: Option<u32>,
        revision: Option<u32>,
    ) -> bool {
        self.vendor_id.is_some()
            && self.vendor_id == vendor_id
            && self.product_code.is_none_or(|p| Some(p) == product_code)
            && self
                .revisions
                .is_none_or(|(min, max)| revision.is_some_and(|r| (min..=max).contains(&r)))
    }
}

impl std::fmt::Display for ExpectedIdentity {
    /// One line: `identity: vendor-ID 0x00000515, revisions 1..=3, fw_release in [242]`; unknown
    /// fields are named as unknown.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let hex = |v: Option<u32>| v.map_or("unknown".to_string(), |v| format!("{v:#010x}"));
        write!(
            f,
            "identity: vendor-ID {}, product code {}",
            hex(self.vendor_id),
            hex(self.product_code)
        )?;
        if let Some((min, max)) = self.revisions {
            write!(f, ", revisions {min:#x}..={max:#x}")?;
        }
        if let Some(parameter) = &self.parameter {
            write!(f, ", {parameter} in {:?}", self.values)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn swd(product_code: Option<u32>, revisions: Option<(u32, u32)>) -> ExpectedIdentity {
        ExpectedIdentity {
            vendor_id: Some(0x515),
            product_code,
            revisions,
            parameter: None,
            values: Vec::new(),
            source: None,
        }
    }

    #[test]
    fn a_node_is_covered_only_with_the_known_vendor_and_the_given_product_and_revisions() {
        let vendor_only = swd(None, None);
        assert!(vendor_only.covers_node(Some(0x515), Some(7), None));
        assert!(!vendor_only.covers_node(Some(0x1234), Some(7), Some(1)));
        assert!(!vendor_only.covers_node(None, None, None));
        let full = swd(Some(7), Some((2, 4)));
        assert!(full.covers_node(Some(0x515), Some(7), Some(4)));
        assert!(!full.covers_node(Some(0x515), Some(8), Some(3)));
        assert!(!full.covers_node(Some(0x515), Some(7), Some(5)));
        assert!(!full.covers_node(Some(0x515), Some(7), None));
        let unknown_vendor = ExpectedIdentity {
            vendor_id: None,
            ..swd(None, None)
        };
        assert!(!unknown_vendor.covers_node(Some(0), None, None));
    }
}

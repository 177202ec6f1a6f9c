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

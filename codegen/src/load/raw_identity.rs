//! `[identity]` as written: the drive, firmware and configuration a description was written for.

use serde::Deserialize;
use toml::Spanned;

use super::raw::RawCitation;

/// `[identity]`: CANopen 1018h values and/or a parameter whose value tells the firmware or
/// parameter configuration, with the values the description covers.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawIdentity {
    pub vendor_id: Option<Spanned<i64>>,
    pub product_code: Option<Spanned<i64>>,
    pub revisions: Option<RawRange>,
    pub parameter: Option<Spanned<String>>,
    #[serde(default)]
    pub values: Vec<Spanned<i64>>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `{ min, max }`, both inclusive.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRange {
    pub min: Spanned<i64>,
    pub max: Spanned<i64>,
}

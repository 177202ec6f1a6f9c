//! `[[ramp]]` as written: the parameters that set how fast the speed follows a setpoint.

use serde::Deserialize;
use toml::Spanned;

use super::raw::RawCitation;

/// `[[ramp]]`: a setpoint's acceleration and deceleration.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRamp {
    pub setpoint: Spanned<String>,
    pub up: Spanned<RawSlope>,
    pub down: Spanned<RawSlope>,
    pub full_scale: Option<String>,
    pub enable: Option<String>,
    pub polarity: Option<RawPolarity>,
    pub doc: Option<String>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `{ time }`, `{ rate }` (optionally `per`) or `{ speed, time }`: one direction of a ramp.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSlope {
    pub time: Option<String>,
    pub rate: Option<String>,
    pub per: Option<String>,
    pub speed: Option<String>,
}

/// `{ parameter, bit }`: the bit that multiplies the setpoint by -1 while set.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPolarity {
    pub parameter: String,
    pub bit: u32,
}

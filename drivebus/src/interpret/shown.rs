//! Raw bytes read from a drive become a value for people (with its unit, enum name or flag
//! names) and for scripts (the engineering number), through the parameter's scale.

use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use super::{Described, Model, RawValue, Symbols};
use crate::DataType;

/// A value read from the drive, ready to print.
#[derive(Debug, Clone, PartialEq)]
pub struct Shown {
    /// The value for people: with its unit, enum name or flag names.
    pub text: String,
    /// The raw value.
    pub raw: Raw,
    /// The engineering value for scripts.
    pub value: Engineering,
}

/// The raw value behind a [`Shown`] value.
#[derive(Debug, Clone, PartialEq)]
pub enum Raw {
    /// The bytes of a string or octet parameter.
    Bytes(Vec<u8>),
    /// A number: an exact integer where the type is one.
    Number(RawValue),
    /// Too few bytes for the type.
    Undecodable,
}

/// The engineering value behind a [`Shown`] value.
#[derive(Debug, Clone, PartialEq)]
pub enum Engineering {
    /// An unscaled integer, exact.
    Int(i128),
    /// A scaled or float value.
    Float(f64),
    /// Names (enum value, flags) or text.
    Text(String),
    /// Not known: the bytes do not decode, or the scale is computed at run time.
    Unknown,
}

/// Decodes the raw bytes of `parameter`.
pub fn show<M: Model>(model: &M, parameter: &M::Parameter, bytes: &[u8]) -> Shown {
    let data_type = parameter.data_type();
    if let DataType::String(_) | DataType::Octets(_) = data_type {
        let text = String::from_utf8_lossy(bytes)
            .trim_end_matches('\0')
            .to_string();
        return Shown {
            raw: Raw::Bytes(bytes.to_vec()),
            value: Engineering::Text(text.clone()),
            text,
        };
    }
    let Some(exact) = RawValue::of(data_type, bytes) else {
        return Shown {
            text: format!("{bytes:02X?}"),
            raw: Raw::Undecodable,
            value: Engineering::Unknown,
        };
    };
    // Enums and flags are over integer types: named from the exact integer, not the float.
    if let RawValue::Int(int) = exact {
        if let Some(names) = names(model.symbols(parameter), int) {
            return Shown {
                value: Engineering::Text(names.clone()),
                text: names,
                raw: Raw::Number(exact),
            };
        }
    }
    let value = match (parameter.fixed_scale(), exact) {
        (Some(scale), RawValue::Int(int)) if scale == crate::Scale::IDENTITY => {
            Engineering::Int(int)
        }
        (Some(scale), raw) => Engineering::Float(engineering(scale, raw)),
        (None, _) => Engineering::Unknown,
    };
    Shown {
        text: show_number(parameter, exact),
        raw: Raw::Number(exact),
        value,
    }
}

/// The names of `raw`: its enum value (or `unknown (N)`), or its flags and any unknown bits.
fn names(symbols: Symbols<'_>, raw: i128) -> Option<String> {
    match symbols {
        Symbols::Plain => None,
        Symbols::Enum { values, .. } => Some(
            values
                .iter()
                .find(|(_, value)| i128::from(*value) == raw)
                .map_or_else(|| format!("unknown ({raw})"), |(name, _)| name.to_string()),
        ),
        Symbols::Flags { bits, .. } => {
            let raw = raw as u64;
            let mut names: Vec<String> = bits
                .iter()
                .filter(|(_, bit)| raw & bit_mask(*bit) != 0)
                .map(|(name, _)| name.to_string())
                .collect();
            let known = bits
                .iter()
                .fold(0u64, |mask, (_, bit)| mask | bit_mask(*bit));
            if raw & !known != 0 {
                names.push(format!("{:#x}", raw & !known));
            }
            Some(if names.is_empty() {
                "(none)".to_string()
            } else {
                names.join("|")
            })
        }
    }
}

/// The mask of bit `bit` of a 64-bit value (none beyond bit 63).
pub(super) fn bit_mask(bit: u32) -> u64 {
    1u64.checked_shl(bit).unwrap_or(0)
}

/// The engineering value of `raw`; exact fractions for integers (3 × 1/10 shows as 0.3).
fn engineering(scale: crate::Scale, raw: RawValue) -> f64 {
    match raw {
        RawValue::Int(int) => i64::try_from(int).map_or_else(
            |_| scale.to_engineering(int as f64),
            |int| scale.to_engineering(int),
        ),
        RawValue::Float(float) => scale.to_engineering(float),
    }
}

/// A raw number in engineering units with the unit (raw when the scale is run-time); an
/// unscaled integer exactly.
pub(super) fn show_number(parameter: &impl Described, raw: RawValue) -> String {
    let unit = unit_suffix(parameter);
    match (parameter.fixed_scale(), raw) {
        (Some(scale), RawValue::Int(int)) if scale == crate::Scale::IDENTITY => {
            format!("{int}{unit}")
        }
        (Some(scale), raw) => format!(
            "{:.*}{unit}",
            decimals_of(scale.factor.to_f64()),
            engineering(scale, raw)
        ),
        (None, raw) => format!("raw {raw}"),
    }
}

/// ` unit`, or nothing for a parameter without one.
pub(super) fn unit_suffix(parameter: &impl Described) -> String {
    parameter
        .unit()
        .map_or(String::new(), |unit| format!(" {unit}"))
}

/// Decimal places needed to show multiples of `step` (at most 6).
fn decimals_of(step: f64) -> usize {
    (0..=6)
        .find(|d| {
            let scaled = step * 10f64.powi(*d as i32);
            (scaled - scaled.round()).abs() < 1e-9
        })
        .unwrap_or(6)
}

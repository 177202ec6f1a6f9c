//! Raw bytes read from a drive become a value for people (with its unit, enum name or flag
//! names) and for scripts (the engineering number), through the parameter's scale.

use core::fmt;
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
    Presentation::of(model, parameter).show(bytes)
}

/// How one parameter's raw bytes are shown, looked up once: for a stream of values of the same
/// parameters (a bus trace), where [`show`] would look up the symbols and unit for every value
/// and build every part of a [`Shown`]. [`text`](Self::text) and [`number`](Self::number) are
/// the parts of [`show`](Self::show), computed alone and without allocating.
#[derive(Debug, Clone, PartialEq)]
pub struct Presentation<'a> {
    data_type: DataType,
    symbols: Symbols<'a>,
    unit: Option<&'a str>,
    scale: Option<crate::Scale>,
}

/// What the bytes of a value are, before they are shown.
enum Reading<'b> {
    /// The bytes of a string or octet parameter.
    Bytes(&'b [u8]),
    /// Too few bytes for the type.
    Undecodable(&'b [u8]),
    /// An integer with names (an enumeration or flags).
    Named(i128),
    /// A number.
    Number(RawValue),
}

impl<'a> Presentation<'a> {
    /// The presentation of `parameter` of `model`.
    pub fn of<M: Model>(model: &'a M, parameter: &'a M::Parameter) -> Self {
        Self {
            data_type: parameter.data_type(),
            symbols: model.symbols(parameter),
            unit: parameter.unit(),
            scale: parameter.fixed_scale(),
        }
    }

    fn read<'b>(&self, bytes: &'b [u8]) -> Reading<'b> {
        if let DataType::String(_) | DataType::Octets(_) = self.data_type {
            return Reading::Bytes(bytes);
        }
        match RawValue::of(self.data_type, bytes) {
            None => Reading::Undecodable(bytes),
            // Enums and flags are over integer types: named from the exact integer, not the float.
            Some(RawValue::Int(int)) if self.symbols != Symbols::Plain => Reading::Named(int),
            Some(raw) => Reading::Number(raw),
        }
    }

    /// The value for people ([`Shown::text`]), written when displayed.
    pub fn text<'b>(&'b self, bytes: &'b [u8]) -> impl fmt::Display + 'b {
        ShownText {
            presentation: self,
            bytes,
        }
    }

    /// The value as one number: the engineering value, an enumeration or flags word by its raw
    /// value, a value of a run-time scale raw; `None` for text and bytes that do not decode.
    pub fn number(&self, bytes: &[u8]) -> Option<f64> {
        match self.read(bytes) {
            Reading::Bytes(_) | Reading::Undecodable(_) => None,
            Reading::Named(int) => Some(int as f64),
            Reading::Number(raw) => Some(match (self.scale, raw) {
                (Some(scale), RawValue::Int(int)) if scale == crate::Scale::IDENTITY => int as f64,
                (Some(scale), raw) => engineering(scale, raw),
                (None, raw) => raw.as_f64(),
            }),
        }
    }

    /// The value, every part of it.
    pub fn show(&self, bytes: &[u8]) -> Shown {
        let text = self.text(bytes).to_string();
        let (raw, value) = match self.read(bytes) {
            Reading::Bytes(bytes) => (Raw::Bytes(bytes.to_vec()), Engineering::Text(text.clone())),
            Reading::Undecodable(_) => (Raw::Undecodable, Engineering::Unknown),
            Reading::Named(int) => (
                Raw::Number(RawValue::Int(int)),
                Engineering::Text(text.clone()),
            ),
            Reading::Number(exact) => {
                let value = match (self.scale, exact) {
                    (Some(scale), RawValue::Int(int)) if scale == crate::Scale::IDENTITY => {
                        Engineering::Int(int)
                    }
                    (Some(scale), raw) => Engineering::Float(engineering(scale, raw)),
                    (None, _) => Engineering::Unknown,
                };
                (Raw::Number(exact), value)
            }
        };
        Shown { text, raw, value }
    }
}

/// [`Presentation::text`].
struct ShownText<'b> {
    presentation: &'b Presentation<'b>,
    bytes: &'b [u8],
}

impl fmt::Display for ShownText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = self.presentation;
        match p.read(self.bytes) {
            Reading::Bytes(bytes) => {
                f.write_str(String::from_utf8_lossy(bytes).trim_end_matches('\0'))
            }
            Reading::Undecodable(bytes) => write!(f, "{bytes:02X?}"),
            Reading::Named(int) => write_names(f, &p.symbols, int),
            Reading::Number(raw) => write_number(f, p.unit, p.scale, raw),
        }
    }
}

/// The names of `raw`: its enum value (or `unknown (N)`), or its flags and any unknown bits
/// (`(none)` for no bit); nothing for plain numbers.
fn write_names(f: &mut fmt::Formatter<'_>, symbols: &Symbols<'_>, raw: i128) -> fmt::Result {
    match symbols {
        Symbols::Plain => Ok(()),
        Symbols::Enum { values, .. } => match values.iter().find(|(_, v)| i128::from(*v) == raw) {
            Some((name, _)) => f.write_str(name),
            None => write!(f, "unknown ({raw})"),
        },
        Symbols::Flags { bits, .. } => {
            let raw = raw as u64;
            let mut separator = "";
            for (name, _) in bits.iter().filter(|(_, bit)| raw & bit_mask(*bit) != 0) {
                write!(f, "{separator}{name}")?;
                separator = "|";
            }
            let known = bits
                .iter()
                .fold(0u64, |mask, (_, bit)| mask | bit_mask(*bit));
            if raw & !known != 0 {
                write!(f, "{separator}{:#x}", raw & !known)?;
                separator = "|";
            }
            if separator.is_empty() {
                f.write_str("(none)")?;
            }
            Ok(())
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
    NumberText {
        unit: parameter.unit(),
        scale: parameter.fixed_scale(),
        raw,
    }
    .to_string()
}

/// [`show_number`], written when displayed.
struct NumberText<'a> {
    unit: Option<&'a str>,
    scale: Option<crate::Scale>,
    raw: RawValue,
}

impl fmt::Display for NumberText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_number(f, self.unit, self.scale, self.raw)
    }
}

/// [`show_number`] to a formatter.
fn write_number(
    f: &mut fmt::Formatter<'_>,
    unit: Option<&str>,
    scale: Option<crate::Scale>,
    raw: RawValue,
) -> fmt::Result {
    match (scale, raw) {
        (Some(scale), RawValue::Int(int)) if scale == crate::Scale::IDENTITY => {
            // The same digits; i64's formatting is the faster where the value fits.
            match i64::try_from(int) {
                Ok(int) => write!(f, "{int}")?,
                Err(_) => write!(f, "{int}")?,
            }
        }
        (Some(scale), raw) => write!(
            f,
            "{:.*}",
            decimals_of(scale.factor.to_f64()),
            engineering(scale, raw)
        )?,
        (None, raw) => return write!(f, "raw {raw}"),
    }
    match unit {
        Some(unit) => write!(f, " {unit}"),
        None => Ok(()),
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

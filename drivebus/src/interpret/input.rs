//! Values as a person types them (`1500rpm`, `velocity`, `run|alarm`, `raw:4950`) become the raw
//! bytes of a described parameter, through the parameter's scale and [`check`].

use core::fmt;
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use super::bounds_check::{check, Breach};
use super::shown::{bit_mask, show_number, unit_suffix};
use super::{raw, Described, Model, RawValue, Symbols};
use crate::scale::EXACT_INTEGERS;
use crate::{DataType, ScaleError};

/// Why a typed value was refused (nothing has been sent).
#[derive(Debug, Clone, PartialEq)]
pub enum InputError {
    /// The text is not a number, enum value or flag list.
    Unparsable(String),
    /// The unit given is not the parameter's.
    WrongUnit {
        /// The unit typed.
        given: String,
        /// The parameter's unit (`None`: the parameter has none).
        expected: Option<String>,
    },
    /// Outside the described range or the type's bounds.
    OutOfRange(String),
    /// Not one of the allowed values.
    NotAllowed(String),
    /// Not a whole number of raw steps.
    NotRepresentable(String),
    /// The scale depends on other parameters; only raw values can be written.
    RuntimeScale(String),
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InputError::WrongUnit {
                given,
                expected: Some(unit),
            } => write!(f, "wrong unit `{given}`: the parameter is in {unit}"),
            InputError::WrongUnit {
                given,
                expected: None,
            } => write!(f, "wrong unit `{given}`: the parameter has no unit"),
            InputError::Unparsable(why)
            | InputError::OutOfRange(why)
            | InputError::NotAllowed(why)
            | InputError::NotRepresentable(why)
            | InputError::RuntimeScale(why) => f.write_str(why),
        }
    }
}

impl std::error::Error for InputError {}

/// Parses `text` into the raw bytes of `parameter`, checking unit, range and allowed values.
///
/// Accepted: a number with or without the parameter's unit (`1500rpm`, `49.5 V`, `1500`), a raw
/// integer (`raw:4950`, `0x1356`), an enum value name, flag names joined by `|`, `true`/`false`.
pub fn parse<M: Model>(
    model: &M,
    parameter: &M::Parameter,
    text: &str,
) -> Result<Vec<u8>, InputError> {
    let text = text.trim();
    let data_type = parameter.data_type();
    if let DataType::String(capacity) | DataType::Octets(capacity) = data_type {
        if text.len() > capacity as usize {
            return Err(InputError::OutOfRange(format!(
                "`{text}` is longer than {capacity} bytes"
            )));
        }
        return Ok(text.as_bytes().to_vec());
    }
    let raw = match symbolic(model.symbols(parameter), parameter, text)? {
        Some(raw) => RawValue::Int(raw),
        None => numeric(parameter, text)?,
    };
    check(parameter, raw).map_err(|breach| refusal(parameter, raw, breach))?;
    Ok(match (data_type, raw) {
        (DataType::F32, raw) => (raw.as_f64() as f32).to_le_bytes().to_vec(),
        (DataType::F64, raw) => raw.as_f64().to_le_bytes().to_vec(),
        // `check` has kept the integer within the type's bounds, so no byte is cut off.
        (_, RawValue::Int(raw)) => raw::from_int(data_type, raw),
        (_, RawValue::Float(raw)) => {
            return Err(InputError::NotRepresentable(format!(
                "{raw} is not a whole raw value of {}",
                parameter.name()
            )))
        }
    })
}

/// An enum value name, flag names, a boolean word or an explicit raw integer.
fn symbolic(
    symbols: Symbols<'_>,
    parameter: &impl Described,
    text: &str,
) -> Result<Option<i128>, InputError> {
    if let Some(raw) = raw_integer(text) {
        return raw.map(Some);
    }
    if parameter.data_type() == DataType::Bool {
        match text {
            "true" | "on" => return Ok(Some(1)),
            "false" | "off" => return Ok(Some(0)),
            _ => {}
        }
    }
    let named = text.starts_with(|c: char| c.is_alphabetic());
    match symbols {
        Symbols::Enum { name, values } => {
            if let Some((_, value)) = values.iter().find(|(v, _)| v.eq_ignore_ascii_case(text)) {
                return Ok(Some(i128::from(*value)));
            }
            if named {
                let names: Vec<&str> = values.iter().map(|(v, _)| *v).collect();
                return Err(InputError::Unparsable(format!(
                    "`{text}` is not a value of {name}; one of: {}",
                    names.join(", ")
                )));
            }
        }
        Symbols::Flags { name, bits } if named => {
            let mut raw = 0u64;
            for typed in text.split(['|', '+', ',']).map(str::trim) {
                let (_, bit) = bits
                    .iter()
                    .find(|(b, _)| b.eq_ignore_ascii_case(typed))
                    .ok_or_else(|| {
                        InputError::Unparsable(format!("`{typed}` is not a bit of {name}"))
                    })?;
                raw |= bit_mask(*bit);
            }
            return Ok(Some(i128::from(raw)));
        }
        _ => {}
    }
    Ok(None)
}

/// `raw:N`, `0xNN` or `0bNN`: a raw value, no scaling, exact.
fn raw_integer(text: &str) -> Option<Result<i128, InputError>> {
    let bad = || InputError::Unparsable(format!("`{text}` is not a raw integer"));
    let (digits, radix) = if let Some(rest) = text.strip_prefix("raw:") {
        (rest.trim(), 10)
    } else if let Some(hex) = text.strip_prefix("0x").or_else(|| text.strip_prefix("0X")) {
        (hex, 16)
    } else if let Some(bin) = text.strip_prefix("0b") {
        (bin, 2)
    } else {
        return None;
    };
    let (negative, digits) = match digits.strip_prefix('-') {
        Some(d) => (true, d),
        None => (false, digits),
    };
    Some(
        i128::from_str_radix(&digits.replace('_', ""), radix)
            .map(|v| if negative { -v } else { v })
            .map_err(|_| bad()),
    )
}

/// A number in engineering units, with an optional unit that must be the parameter's: a whole
/// raw value for integer types (exact where the scale is one), a float for float types.
fn numeric(parameter: &impl Described, text: &str) -> Result<RawValue, InputError> {
    let split = text
        .char_indices()
        .find(|&(i, c)| !(c.is_ascii_digit() || c == '.' || ((c == '-' || c == '+') && i == 0)))
        .map_or(text.len(), |(i, _)| i);
    let (number, unit) = text.split_at(split);
    let value: f64 = number.parse().map_err(|_| {
        InputError::Unparsable(format!(
            "`{text}` is not a value: give a number (with its unit), an enum value or raw:N"
        ))
    })?;
    check_unit(parameter, unit.trim())?;
    let Some(scale) = parameter.fixed_scale() else {
        return Err(InputError::RuntimeScale(format!(
            "the scale of {} is computed at run time from other parameters; give a raw value (raw:N)",
            parameter.name()
        )));
    };
    let data_type = parameter.data_type();
    if data_type.integer_bounds().is_some() && scale == crate::Scale::IDENTITY {
        if let Ok(exact) = number.trim_start_matches('+').parse::<i128>() {
            return Ok(RawValue::Int(exact));
        }
    }
    // Otherwise converted as generated crates convert (`drivebus::Scale::to_raw`).
    let refused = |error: ScaleError| match error {
        ScaleError::BetweenSteps { .. } => InputError::NotRepresentable(format!(
            "{text} is not a multiple of the parameter's step {}{}",
            scale.factor.to_f64(),
            unit_suffix(parameter)
        )),
        _ => InputError::OutOfRange(format!("{text} does not fit {}", data_type.name())),
    };
    let raw = match data_type {
        DataType::F32 => scale
            .to_raw::<f32>(value)
            .map(f64::from)
            .map(RawValue::Float),
        DataType::F64 => scale.to_raw::<f64>(value).map(RawValue::Float),
        DataType::Signed(_) => scale.to_raw::<i64>(value).map(|r| RawValue::Int(r.into())),
        _ => scale.to_raw::<u64>(value).map(|r| RawValue::Int(r.into())),
    }
    .map_err(refused)?;
    match raw {
        RawValue::Int(int) if int.unsigned_abs() as f64 >= EXACT_INTEGERS => {
            Err(InputError::NotRepresentable(format!(
                "{text} is beyond the integers a float holds exactly; give the raw value (raw:N)"
            )))
        }
        raw => Ok(raw),
    }
}

fn check_unit(parameter: &impl Described, given: &str) -> Result<(), InputError> {
    if given.is_empty() {
        return Ok(());
    }
    let normalize = |u: &str| u.trim_start_matches('°').to_ascii_lowercase();
    match parameter.unit() {
        Some(unit) if normalize(unit) == normalize(given) => Ok(()),
        expected => Err(InputError::WrongUnit {
            given: given.to_string(),
            expected: expected.map(str::to_string),
        }),
    }
}

/// The message for a value [`check`] refused, in the parameter's units.
fn refusal(parameter: &impl Described, raw: RawValue, breach: Breach) -> InputError {
    let shown = |r: RawValue| show_number(parameter, r);
    let bound = |n: super::Number| shown(n.into());
    let value = shown(raw);
    let name = parameter.name();
    match breach {
        Breach::OutsideType => {
            let (min, max) = parameter.data_type().integer_bounds().unwrap_or_default();
            InputError::OutOfRange(format!(
                "{value} does not fit {} ({}..={})",
                parameter.data_type().name(),
                shown(RawValue::Int(min)),
                shown(RawValue::Int(max))
            ))
        }
        Breach::BelowRange | Breach::AboveRange | Breach::Unordered => {
            let range = parameter.range().map_or_else(String::new, |range| {
                format!("{}..={}", bound(range.min), bound(range.max))
            });
            InputError::OutOfRange(format!("{value} is outside the range of {name}: {range}"))
        }
        Breach::NotAllowed => {
            let allowed: Vec<String> = parameter.allowed().iter().map(|a| bound(*a)).collect();
            InputError::NotAllowed(format!(
                "{value} is not allowed for {name}; allowed: {}",
                allowed.join(", ")
            ))
        }
    }
}

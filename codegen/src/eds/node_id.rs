//! Numeric EDS values: decimal, hex, negative hex, floats, and `$NODEID` terms kept symbolic.
//!
//! `$NODEID+0x180`, `0x180+$NODEID` and `$NodeID + 0x200` all mean "the node id plus 384"; the
//! value stays a function of the node id (a COB-ID default differs on every node). A REAL32 or
//! REAL64 value written in hex is its IEEE-754 bit pattern (`0x41200000` is 10.0).

use drivebus_model::canopen::NodeId;

use super::trim::trim;
use crate::ir::{DataType, Number};

/// A value of `DefaultValue`, `LowLimit`, `HighLimit` or `ParameterValue`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EdsValue {
    /// A constant.
    Number(Number),
    /// The node id plus this offset.
    NodeIdPlus(i64),
}

/// Parses `text` as a value of type `ty`. `Ok(None)` for types whose values the IR does not keep
/// (strings, octets); `Err` says what is wrong.
pub fn parse_value(text: &str, ty: DataType) -> Result<Option<EdsValue>, String> {
    match ty {
        DataType::String(_) | DataType::Octets(_) => Ok(None),
        DataType::F32 | DataType::F64 => parse_float(text, ty).map(|f| Some(EdsValue::Number(f))),
        DataType::Bool => parse_bool(text).map(|b| Some(EdsValue::Number(Number::Int(b)))),
        DataType::Unsigned(_) | DataType::Signed(_) => parse_integer(text, ty).map(Some),
    }
}

fn parse_float(text: &str, ty: DataType) -> Result<Number, String> {
    let t = trim(text);
    if let Some(digits) = float_bit_digits(t) {
        return float_from_bits(t, digits, ty);
    }
    if is_signed_hex(t) {
        return Err(format!(
            "`{t}`: a float in hex is its IEEE-754 bit pattern, which takes no sign"
        ));
    }
    match t.parse::<f64>() {
        Ok(f) if f.is_finite() => fit_f32(f, ty)
            .map(Number::Float)
            .ok_or_else(|| format!("`{t}` does not fit f32")),
        _ => Err(format!("`{t}` is not a number")),
    }
}

/// A REAL32 value written a hair beyond the largest `f32` (`3.4028235E+38`, how `FLT_MAX` is
/// printed) is that `f32`, the same value on the wire; one beyond any `f32` does not fit.
fn fit_f32(f: f64, ty: DataType) -> Option<f64> {
    if ty != DataType::F32 || f.abs() <= f64::from(f32::MAX) {
        return Some(f);
    }
    // Rounding to the nearest f32 is the point.
    let nearest = f as f32;
    nearest.is_finite().then(|| f64::from(nearest))
}

/// Whether `text`, a value of type `ty`, is a float written as its IEEE-754 bit pattern.
pub fn is_float_bit_pattern(text: &str, ty: DataType) -> bool {
    matches!(ty, DataType::F32 | DataType::F64) && float_bit_digits(trim(text)).is_some()
}

/// The hex digits of `0x...` (no sign).
fn float_bit_digits(t: &str) -> Option<&str> {
    t.strip_prefix("0x").or_else(|| t.strip_prefix("0X"))
}

fn is_signed_hex(t: &str) -> bool {
    t.strip_prefix(['-', '+'])
        .and_then(float_bit_digits)
        .is_some()
}

/// The float whose REAL32 / REAL64 bits are the hex `digits` (of the value `t`).
fn float_from_bits(t: &str, digits: &str, ty: DataType) -> Result<Number, String> {
    let width = if ty == DataType::F32 { 8 } else { 16 };
    let name = if ty == DataType::F32 {
        "REAL32"
    } else {
        "REAL64"
    };
    if digits.is_empty() || digits.len() > width {
        return Err(format!(
            "`{t}` is not a {name} bit pattern (1 to {width} hex digits)"
        ));
    }
    let bits = digits_value(digits, 16)
        .and_then(|b| u64::try_from(b).ok())
        .ok_or_else(|| format!("`{t}` is not a {name} bit pattern (1 to {width} hex digits)"))?;
    let value = match u32::try_from(bits) {
        Ok(bits) if ty == DataType::F32 => f64::from(f32::from_bits(bits)),
        _ => f64::from_bits(bits),
    };
    if value.is_finite() {
        Ok(Number::Float(value))
    } else {
        Err(format!(
            "`{t}` is the {name} bit pattern of {value}, not a number"
        ))
    }
}

fn parse_bool(text: &str) -> Result<i64, String> {
    match trim(text).to_ascii_lowercase().as_str() {
        "true" => Ok(1),
        "false" => Ok(0),
        t => match parse_int(t) {
            Some((v @ (0 | 1), _)) => Ok(v as i64),
            _ => Err(format!("`{t}` is not a boolean (0 or 1)")),
        },
    }
}

/// `$NODEID` and integer terms joined by `+`; hex beyond a signed type's maximum is two's complement.
fn parse_integer(text: &str, ty: DataType) -> Result<EdsValue, String> {
    let compact = trim(text);
    if compact.is_empty() {
        return Err("the value is empty".into());
    }
    let mut node_terms = 0;
    let mut sum: i128 = 0;
    for term in terms(compact) {
        if term.eq_ignore_ascii_case("$nodeid") {
            node_terms += 1;
            continue;
        }
        let (value, hex) = parse_int(term).ok_or_else(|| match term {
            "" => format!("`{compact}` has an empty term"),
            t if t.starts_with('$') => format!("`{t}` is not `$NODEID`"),
            t => format!("`{t}` is not an integer"),
        })?;
        sum += wrap_signed_hex(value, hex, ty);
    }
    if node_terms > 1 {
        return Err(format!("`{compact}` names `$NODEID` more than once"));
    }
    let (min, max) = ty.integer_bounds().unwrap_or((i128::MIN, i128::MAX));
    if node_terms == 1 {
        let (lowest, highest) = (sum + i128::from(NodeId::MIN), sum + i128::from(NodeId::MAX));
        if lowest < min || highest > max {
            return Err(format!(
                "$NODEID+{sum} does not fit {} for every node ID {}..={} ({lowest}..={highest})",
                ty.name(),
                NodeId::MIN,
                NodeId::MAX
            ));
        }
    } else if sum < min || sum > max {
        return Err(format!("{sum} does not fit {}", ty.name()));
    }
    let value = i64::try_from(sum).map_err(|_| format!("{sum} does not fit {}", ty.name()))?;
    Ok(if node_terms == 1 {
        EdsValue::NodeIdPlus(value)
    } else {
        EdsValue::Number(Number::Int(value))
    })
}

/// The `+`-separated terms of `text`, trimmed (`str::split` costs more on such short texts).
fn terms(text: &str) -> impl Iterator<Item = &str> {
    let mut rest = Some(text);
    std::iter::from_fn(move || {
        let current = rest?;
        let (term, next) = match current.bytes().position(|b| b == b'+') {
            Some(plus) => (&current[..plus], Some(&current[plus + 1..])),
            None => (current, None),
        };
        rest = next;
        Some(trim(term))
    })
}

/// An integer term: decimal or `0x` hex, either with a leading `-`. Returns the value and whether
/// it was written in hex.
fn parse_int(term: &str) -> Option<(i128, bool)> {
    let (negative, digits) = match term.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, term.strip_prefix('+').unwrap_or(term)),
    };
    let (magnitude, hex) = match digits
        .strip_prefix("0x")
        .or_else(|| digits.strip_prefix("0X"))
    {
        // A `+` may lead hex digits, as `u64::from_str_radix` allows.
        Some(hex) if !hex.is_empty() && hex.len() <= 16 => {
            let hex = hex
                .strip_prefix('+')
                .filter(|h| !h.is_empty())
                .unwrap_or(hex);
            (digits_value(hex, 16)?, true)
        }
        Some(_) => return None,
        None if !digits.is_empty() && digits.len() <= 20 => (digits_value(digits, 10)?, false),
        None => return None,
    };
    Some((if negative { -magnitude } else { magnitude }, hex))
}

/// The value of `digits` in `radix`, digit by digit: these are short, and at most 16 hex or 20
/// decimal digits cannot overflow an `i128`.
fn digits_value(digits: &str, radix: u32) -> Option<i128> {
    digits.bytes().try_fold(0i128, |n, b| {
        let digit = char::from(b).to_digit(radix)?;
        Some(n * i128::from(radix) + i128::from(digit))
    })
}

/// `0xFFFF` for an INTEGER16 is the bit pattern of -1, as CANopen tools write it.
fn wrap_signed_hex(value: i128, hex: bool, ty: DataType) -> i128 {
    match ty {
        DataType::Signed(bytes) if hex && value > 0 => {
            let bits = u32::from(bytes) * 8;
            let half = 1i128 << (bits - 1);
            if value >= half && value < 2 * half {
                value - 2 * half
            } else {
                value
            }
        }
        _ => value,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const U32: DataType = DataType::Unsigned(4);

    fn int(text: &str, ty: DataType) -> EdsValue {
        parse_value(text, ty).unwrap().unwrap()
    }

    #[test]
    fn node_id_terms_in_every_order_and_spelling() {
        for text in [
            "$NODEID+0x180",
            "0x180+$NODEID",
            "$NodeID + 0x180",
            " 384 + $nodeid ",
        ] {
            assert_eq!(int(text, U32), EdsValue::NodeIdPlus(0x180), "{text}");
        }
        assert_eq!(int("$NODEID", U32), EdsValue::NodeIdPlus(0));
        assert!(parse_value("$NODEID+$NODEID", U32).is_err());
        assert!(parse_value("$NODE+1", U32).is_err());
    }

    #[test]
    fn decimal_hex_and_negative_hex() {
        let i16_ = DataType::Signed(2);
        assert_eq!(int("-0x10", i16_), EdsValue::Number(Number::Int(-16)));
        assert_eq!(int("0xFFFF", i16_), EdsValue::Number(Number::Int(-1)));
        assert_eq!(int("-200", i16_), EdsValue::Number(Number::Int(-200)));
        assert_eq!(int("0X1f", U32), EdsValue::Number(Number::Int(31)));
        assert!(parse_value("0x1FFFF", i16_).is_err());
        assert!(parse_value("-1", U32).is_err());
        assert!(parse_value("12abc", U32).is_err());
        assert_eq!(
            int("99999999999999999999", DataType::F64),
            EdsValue::Number(Number::Float(1e20))
        );
        let float = DataType::F64;
        assert!(parse_value("0x+1F", float).is_err());
        assert!(parse_value("-0x1F", float).is_err());
        assert!(parse_value("0x+", U32).is_err());
        assert!(parse_value("0x-1", U32).is_err());
        assert!(parse_value("1_000", U32).is_err());
    }

    #[test]
    fn hex_floats_are_bit_patterns() {
        let f32_ = DataType::F32;
        assert_eq!(
            int("0x41200000", f32_),
            EdsValue::Number(Number::Float(10.0))
        );
        assert_eq!(
            int("0x40490FDB", f32_),
            EdsValue::Number(Number::Float(f64::from(std::f32::consts::PI)))
        );
        assert_eq!(
            int("0x400921FB54442D18", DataType::F64),
            EdsValue::Number(Number::Float(std::f64::consts::PI))
        );
        assert_eq!(int("0x0", f32_), EdsValue::Number(Number::Float(0.0)));
        assert!(parse_value("0x7FC00000", f32_).is_err(), "NaN");
        assert!(parse_value("0x7F800000", f32_).is_err(), "infinity");
        assert!(parse_value("0x141200000", f32_).is_err(), "nine digits");
        assert!(parse_value("0x", f32_).is_err());
        assert_eq!(
            int("-3.4028235E+38", f32_),
            EdsValue::Number(Number::Float(f64::from(f32::MIN)))
        );
        assert_eq!(
            int("3.4028235E+38", DataType::F64),
            EdsValue::Number(Number::Float(3.4028235e38))
        );
        assert!(parse_value("3.5e38", f32_).is_err());
        assert!(is_float_bit_pattern(" 0X3F800000 ", f32_));
        assert!(!is_float_bit_pattern("0x3F800000", DataType::Unsigned(4)));
        assert!(!is_float_bit_pattern("1.5", f32_));
    }

    #[test]
    fn floats_bools_and_strings() {
        assert_eq!(
            int("1.5", DataType::F32),
            EdsValue::Number(Number::Float(1.5))
        );
        assert_eq!(
            int("TRUE", DataType::Bool),
            EdsValue::Number(Number::Int(1))
        );
        assert!(parse_value("2", DataType::Bool).is_err());
        assert_eq!(parse_value("hello", DataType::String(8)), Ok(None));
    }
}

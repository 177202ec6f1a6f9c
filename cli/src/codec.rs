//! The dynamic codec: a parameter of the IR and a value as typed on the command line become raw
//! bytes, and raw bytes become a value with its unit, enum name or flag names. It works from the
//! description at run time, not from a generated crate.

use std::cmp::Ordering;
use std::fmt;

use drivebus::interpret::raw;
use drivebus::scale::EXACT_INTEGERS;
use drivebus::ValueError;
use drivegen::ir::{DataType, Device, Parameter, Scale};

use drivebus::interpret::RawValue;

/// Why a value typed by the user was refused (nothing has been sent).
#[derive(Debug, Clone, PartialEq)]
pub enum CodecError {
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

impl fmt::Display for CodecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CodecError::Unparsable(why) => write!(f, "{why}"),
            CodecError::WrongUnit {
                given,
                expected: Some(unit),
            } => {
                write!(f, "wrong unit `{given}`: the parameter is in {unit}")
            }
            CodecError::WrongUnit {
                given,
                expected: None,
            } => {
                write!(f, "wrong unit `{given}`: the parameter has no unit")
            }
            CodecError::OutOfRange(why)
            | CodecError::NotAllowed(why)
            | CodecError::NotRepresentable(why)
            | CodecError::RuntimeScale(why) => write!(f, "{why}"),
        }
    }
}

/// An exact affine scale: `value = raw × factor + offset`, converted as generated crates convert
/// (`drivebus::Scale`), plus how to print it.
#[derive(Debug, Clone, Copy)]
struct Affine {
    exact: drivebus::Scale,
    /// Decimal places that show one raw step.
    decimals: usize,
}

impl Affine {
    /// Whether engineering values are the raw values themselves.
    fn is_identity(&self) -> bool {
        self.exact == drivebus::Scale::IDENTITY
    }

    /// The factor, as a float.
    fn factor(&self) -> f64 {
        self.exact.factor.to_f64()
    }

    /// The engineering value of `raw`; exact fractions for integers (3 × 1/10 shows as 0.3).
    fn engineering(&self, raw: RawValue) -> f64 {
        match raw {
            RawValue::Int(int) => i64::try_from(int).map_or_else(
                |_| self.exact.to_engineering(int as f64),
                |int| self.exact.to_engineering(int),
            ),
            RawValue::Float(float) => self.exact.to_engineering(float),
        }
    }
}

/// The fixed scale of `parameter` (identity without one); `None` for a run-time scale.
fn affine(parameter: &Parameter) -> Option<Affine> {
    let (exact, decimals) = match &parameter.scale {
        None => (drivebus::Scale::IDENTITY, 0),
        Some(Scale::Fixed(scale)) => (*scale, decimals_of(scale.factor.to_f64())),
        Some(Scale::Runtime { .. }) => return None,
    };
    Some(Affine { exact, decimals })
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

/// Parses `text` into the raw bytes of `parameter`, checking unit, range and allowed values.
///
/// Accepted: a number with or without the parameter's unit (`1500rpm`, `49.5 V`, `1500`), a raw
/// integer (`raw:4950`, `0x1356`), an enum value name, flag names joined by `|`, `true`/`false`.
pub fn parse(device: &Device, parameter: &Parameter, text: &str) -> Result<Vec<u8>, CodecError> {
    let text = text.trim();
    let data_type = parameter.data_type;
    if let DataType::String(capacity) | DataType::Octets(capacity) = data_type {
        if text.len() > capacity as usize {
            return Err(CodecError::OutOfRange(format!(
                "`{text}` is longer than {capacity} bytes"
            )));
        }
        return Ok(text.as_bytes().to_vec());
    }
    let raw = match symbolic(device, parameter, text)? {
        Some(raw) => RawValue::Int(raw),
        None => numeric(parameter, text)?,
    };
    check(parameter, raw)?;
    Ok(match (data_type, raw) {
        (DataType::F32, raw) => (raw.as_f64() as f32).to_le_bytes().to_vec(),
        (DataType::F64, raw) => raw.as_f64().to_le_bytes().to_vec(),
        // `check` has kept the integer within the type's bounds, so no byte is cut off.
        (_, RawValue::Int(raw)) => raw::from_int(data_type, raw),
        (_, RawValue::Float(raw)) => {
            return Err(CodecError::NotRepresentable(format!(
                "{raw} is not a whole raw value of {}",
                parameter.name
            )))
        }
    })
}

/// An enum value name, flag names, a boolean word or an explicit raw integer.
fn symbolic(
    device: &Device,
    parameter: &Parameter,
    text: &str,
) -> Result<Option<i128>, CodecError> {
    if let Some(raw) = raw_integer(text) {
        return raw.map(Some);
    }
    if parameter.data_type == DataType::Bool {
        match text {
            "true" | "on" => return Ok(Some(1)),
            "false" | "off" => return Ok(Some(0)),
            _ => {}
        }
    }
    if let Some(e) = parameter
        .enumeration
        .as_deref()
        .and_then(|e| device.enumeration(e))
    {
        if let Some(v) = e.values.iter().find(|v| v.name.eq_ignore_ascii_case(text)) {
            return Ok(Some(i128::from(v.value)));
        }
        if text.starts_with(|c: char| c.is_alphabetic()) {
            let names: Vec<&str> = e.values.iter().map(|v| v.name.as_str()).collect();
            return Err(CodecError::Unparsable(format!(
                "`{text}` is not a value of {}; one of: {}",
                e.name,
                names.join(", ")
            )));
        }
    }
    if let Some(flags) = parameter
        .flags
        .as_deref()
        .and_then(|f| device.flags_type(f))
    {
        if text.starts_with(|c: char| c.is_alphabetic()) {
            let mut raw = 0u64;
            for name in text.split(['|', '+', ',']).map(str::trim) {
                let bit = flags
                    .bits
                    .iter()
                    .find(|b| b.name.eq_ignore_ascii_case(name))
                    .ok_or_else(|| {
                        CodecError::Unparsable(format!("`{name}` is not a bit of {}", flags.name))
                    })?;
                raw |= 1 << bit.bit;
            }
            return Ok(Some(i128::from(raw)));
        }
    }
    Ok(None)
}

/// `raw:N`, `0xNN` or `0bNN`: a raw value, no scaling, exact.
fn raw_integer(text: &str) -> Option<Result<i128, CodecError>> {
    let bad = || CodecError::Unparsable(format!("`{text}` is not a raw integer"));
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
fn numeric(parameter: &Parameter, text: &str) -> Result<RawValue, CodecError> {
    let split = text
        .char_indices()
        .find(|&(i, c)| !(c.is_ascii_digit() || c == '.' || ((c == '-' || c == '+') && i == 0)))
        .map_or(text.len(), |(i, _)| i);
    let (number, unit) = text.split_at(split);
    let value: f64 = number.parse().map_err(|_| {
        CodecError::Unparsable(format!(
            "`{text}` is not a value: give a number (with its unit), an enum value or raw:N"
        ))
    })?;
    check_unit(parameter, unit.trim())?;
    let Some(scale) = affine(parameter) else {
        return Err(CodecError::RuntimeScale(format!(
            "the scale of {} is computed at run time from other parameters; give a raw value (raw:N)",
            parameter.name
        )));
    };
    let integer = parameter.data_type.integer_bounds().is_some();
    if integer && scale.is_identity() {
        if let Ok(exact) = number.trim_start_matches('+').parse::<i128>() {
            return Ok(RawValue::Int(exact));
        }
    }
    // Otherwise converted as generated crates convert (`drivebus::Scale::to_raw`).
    let refused = |error: ValueError| match error {
        ValueError::NotRepresentable { .. } => CodecError::NotRepresentable(format!(
            "{text} is not a multiple of the parameter's step {}{}",
            scale.factor(),
            unit_suffix(parameter)
        )),
        _ => CodecError::OutOfRange(format!(
            "{text} does not fit {}",
            parameter.data_type.name()
        )),
    };
    let exact = scale.exact;
    let raw = match parameter.data_type {
        DataType::F32 => exact
            .to_raw::<f32>("", value)
            .map(f64::from)
            .map(RawValue::Float),
        DataType::F64 => exact.to_raw::<f64>("", value).map(RawValue::Float),
        DataType::Signed(_) => exact
            .to_raw::<i64>("", value)
            .map(|r| RawValue::Int(r.into())),
        _ => exact
            .to_raw::<u64>("", value)
            .map(|r| RawValue::Int(r.into())),
    }
    .map_err(refused)?;
    match raw {
        RawValue::Int(int) if int.unsigned_abs() as f64 >= EXACT_INTEGERS => {
            Err(CodecError::NotRepresentable(format!(
                "{text} is beyond the integers a float holds exactly; give the raw value (raw:N)"
            )))
        }
        raw => Ok(raw),
    }
}

fn check_unit(parameter: &Parameter, given: &str) -> Result<(), CodecError> {
    if given.is_empty() {
        return Ok(());
    }
    let normalize = |u: &str| u.trim_start_matches('°').to_ascii_lowercase();
    match &parameter.unit {
        Some(unit) if normalize(unit) == normalize(given) => Ok(()),
        expected => Err(CodecError::WrongUnit {
            given: given.to_string(),
            expected: expected.clone(),
        }),
    }
}

fn unit_suffix(parameter: &Parameter) -> String {
    parameter
        .unit
        .as_deref()
        .map_or(String::new(), |u| format!(" {u}"))
}

/// Checks a raw value against the type's bounds, the range and the allowed values.
fn check(parameter: &Parameter, raw: RawValue) -> Result<(), CodecError> {
    let shown = |r: RawValue| show_number(parameter, r);
    let shown_number = |n: drivegen::ir::Number| match n {
        drivegen::ir::Number::Int(i) => shown(RawValue::Int(i.into())),
        drivegen::ir::Number::Float(f) => shown(RawValue::Float(f)),
    };
    if let (Some((min, max)), RawValue::Int(int)) = (parameter.data_type.integer_bounds(), raw) {
        if int < min || int > max {
            return Err(CodecError::OutOfRange(format!(
                "{} does not fit {} ({}..={})",
                shown(raw),
                parameter.data_type.name(),
                shown(RawValue::Int(min)),
                shown(RawValue::Int(max))
            )));
        }
    }
    let against = |bound: drivegen::ir::Number| bound.compare_raw(raw);
    if let Some(range) = &parameter.range {
        if range.locate(against) != Some(Ordering::Equal) {
            return Err(CodecError::OutOfRange(format!(
                "{} is outside the range of {}: {}..={}",
                shown(raw),
                parameter.name,
                shown_number(range.min),
                shown_number(range.max)
            )));
        }
    }
    if !parameter.allows(against) {
        let allowed: Vec<String> = parameter.allowed.iter().map(|a| shown_number(*a)).collect();
        return Err(CodecError::NotAllowed(format!(
            "{} is not allowed for {}; allowed: {}",
            shown(raw),
            parameter.name,
            allowed.join(", ")
        )));
    }
    Ok(())
}

/// A raw number in engineering units with the unit (raw when the scale is run-time); an
/// unscaled integer exactly.
fn show_number(parameter: &Parameter, raw: RawValue) -> String {
    match (affine(parameter), raw) {
        (Some(scale), RawValue::Int(int)) if scale.is_identity() => {
            format!("{int}{}", unit_suffix(parameter))
        }
        (Some(scale), raw) => format!(
            "{:.*}{}",
            scale.decimals,
            scale.engineering(raw),
            unit_suffix(parameter)
        ),
        (None, raw) => format!("raw {raw}"),
    }
}

/// A value read from the drive, ready to print.
#[derive(Debug, Clone, PartialEq)]
pub struct Shown {
    /// The value for people: with its unit, enum name or flag names.
    pub text: String,
    /// The raw value (an integer where the type is one).
    pub raw: serde_json::Value,
    /// The engineering value for scripts (a number, or the text of names and strings).
    pub value: serde_json::Value,
}

/// Decodes the raw bytes of `parameter`.
pub fn show(device: &Device, parameter: &Parameter, bytes: &[u8]) -> Shown {
    let data_type = parameter.data_type;
    if let DataType::String(_) | DataType::Octets(_) = data_type {
        let text = String::from_utf8_lossy(bytes)
            .trim_end_matches('\0')
            .to_string();
        return Shown {
            raw: serde_json::Value::from(bytes.to_vec()),
            value: serde_json::Value::from(text.clone()),
            text,
        };
    }
    let Some(raw) = raw::to_f64(data_type, bytes) else {
        return Shown {
            text: format!("{bytes:02X?}"),
            raw: serde_json::Value::Null,
            value: serde_json::Value::Null,
        };
    };
    let int = raw::to_int(data_type, bytes);
    let raw_json = int.map_or(serde_json::Value::from(raw), exact_json);
    // Enums and flags are over integer types: named from the exact integer, not the float.
    let names = int.and_then(|int| {
        enum_name(device, parameter, int).or_else(|| flag_names(device, parameter, int as u64))
    });
    if let Some(names) = names {
        return Shown {
            value: serde_json::Value::from(names.clone()),
            text: names,
            raw: raw_json,
        };
    }
    let exact = int.map_or(RawValue::Float(raw), RawValue::Int);
    let value = match (affine(parameter), int) {
        (Some(scale), Some(int)) if scale.is_identity() => exact_json(int),
        (Some(scale), _) => serde_json::Value::from(scale.engineering(exact)),
        (None, _) => serde_json::Value::Null,
    };
    Shown {
        text: show_number(parameter, exact),
        raw: raw_json,
        value,
    }
}

/// An integer as a JSON number, exact for every 64-bit value (JSON readers that parse numbers
/// as doubles may still round it; those that keep integers get it whole).
fn exact_json(int: i128) -> serde_json::Value {
    match (i64::try_from(int), u64::try_from(int)) {
        (Ok(i), _) => serde_json::Value::from(i),
        (_, Ok(u)) => serde_json::Value::from(u),
        _ => serde_json::Value::from(int as f64),
    }
}

fn enum_name(device: &Device, parameter: &Parameter, raw: i128) -> Option<String> {
    let e = device.enumeration(parameter.enumeration.as_deref()?)?;
    Some(
        e.values
            .iter()
            .find(|v| i128::from(v.value) == raw)
            .map_or_else(|| format!("unknown ({raw})"), |v| v.name.clone()),
    )
}

fn flag_names(device: &Device, parameter: &Parameter, raw: u64) -> Option<String> {
    let flags = device.flags_type(parameter.flags.as_deref()?)?;
    let mut names: Vec<String> = flags
        .bits
        .iter()
        .filter(|b| raw & (1 << b.bit) != 0)
        .map(|b| b.name.clone())
        .collect();
    let known = flags.bits.iter().fold(0u64, |m, b| m | 1 << b.bit);
    if raw & !known != 0 {
        names.push(format!("{:#x}", raw & !known));
    }
    Some(if names.is_empty() {
        "(none)".to_string()
    } else {
        names.join("|")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lafert() -> Device {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../descriptions/lafert-smartris"
        );
        drivegen::check(std::path::Path::new(path)).device.unwrap()
    }

    fn parsed(name: &str, text: &str) -> Result<Vec<u8>, CodecError> {
        let device = lafert();
        let parameter = device.parameter(name).unwrap().clone();
        parse(&device, &parameter, text)
    }

    #[test]
    fn engineering_values_become_raw_bytes() {
        assert_eq!(
            parsed("speed_setpoint", "1500rpm"),
            Ok(1500i16.to_le_bytes().to_vec())
        );
        assert_eq!(
            parsed("speed_setpoint", "-3000 rpm"),
            Ok((-3000i16).to_le_bytes().to_vec())
        );
        assert_eq!(
            parsed("torque_setpoint", "2Arms"),
            Ok(200i16.to_le_bytes().to_vec())
        );
        assert_eq!(
            parsed("speed_setpoint", "raw:1000"),
            Ok(1000i16.to_le_bytes().to_vec())
        );
    }

    #[test]
    fn names_become_raw_values() {
        assert_eq!(
            parsed("operation_mode", "velocity"),
            Ok(2u16.to_le_bytes().to_vec())
        );
        assert_eq!(
            parsed("control_word", "run|stop_disabled"),
            Ok(3u16.to_le_bytes().to_vec())
        );
    }

    #[test]
    fn wrong_units_and_ranges_are_refused() {
        assert!(matches!(
            parsed("speed_setpoint", "1500V"),
            Err(CodecError::WrongUnit { .. })
        ));
        assert!(matches!(
            parsed("control_word", "8"),
            Err(CodecError::OutOfRange(_))
        ));
        assert!(matches!(
            parsed("speed_setpoint", "40000rpm"),
            Err(CodecError::OutOfRange(_))
        ));
        assert!(matches!(
            parsed("operation_mode", "none"),
            Err(CodecError::NotAllowed(_))
        ));
        assert!(matches!(
            parsed("torque_setpoint", "2.005Arms"),
            Err(CodecError::NotRepresentable(_))
        ));
        assert!(matches!(
            parsed("operation_mode", "fast"),
            Err(CodecError::Unparsable(_))
        ));
    }

    /// A description of one unscaled and one scaled `u64`: values beyond 2^53 must not pass
    /// through a float.
    fn wide() -> Device {
        let mut device = lafert();
        let template = device.parameter("speed_setpoint").unwrap().clone();
        device.parameters = ["plain", "scaled"]
            .into_iter()
            .map(|name| Parameter {
                name: name.into(),
                data_type: DataType::Unsigned(8),
                range: None,
                allowed: Vec::new(),
                unit: None,
                scale: (name == "scaled")
                    .then_some(Scale::Fixed(drivebus::Scale::fixed(1, 10, 0, 1))),
                ..template.clone()
            })
            .collect();
        device
    }

    #[test]
    fn floats_beyond_their_width_are_refused_not_sent_as_infinity() {
        let device = lafert();
        let mut gain = device.parameter("speed_setpoint").unwrap().clone();
        (gain.data_type, gain.range, gain.unit) = (DataType::F32, None, None);
        let huge = format!("1{}", "0".repeat(40));
        assert!(matches!(
            parse(&device, &gain, &huge),
            Err(CodecError::OutOfRange(_))
        ));
        assert_eq!(
            parse(&device, &gain, "1.5"),
            Ok(1.5f32.to_le_bytes().to_vec())
        );
    }

    #[test]
    fn wide_enum_values_are_named_exactly() {
        let mut device = lafert();
        let e = device
            .enums
            .iter_mut()
            .find(|e| e.name == "operation_mode")
            .unwrap();
        e.data_type = DataType::Signed(8);
        e.values.truncate(2);
        (e.values[0].name, e.values[0].value) = ("near".into(), i64::MAX - 1);
        (e.values[1].name, e.values[1].value) = ("top".into(), i64::MAX);
        let mut mode = device.parameter("operation_mode").unwrap().clone();
        mode.data_type = DataType::Signed(8);
        mode.allowed.clear();
        // As floats both values are 2^63: only an exact comparison tells them apart.
        let shown = show(&device, &mode, &i64::MAX.to_le_bytes());
        assert_eq!(shown.text, "top");
        assert_eq!(
            parse(&device, &mode, "top"),
            Ok(i64::MAX.to_le_bytes().to_vec())
        );
    }

    #[test]
    fn wide_integers_stay_exact() {
        let device = wide();
        let plain = device.parameter("plain").unwrap();
        for text in [
            "raw:18446744073709551610",
            "18446744073709551610",
            "0xFFFFFFFFFFFFFFFA",
        ] {
            let bytes = parse(&device, plain, text).unwrap();
            assert_eq!(bytes, (u64::MAX - 5).to_le_bytes(), "{text}");
            let shown = show(&device, plain, &bytes);
            assert_eq!(shown.text, "18446744073709551610");
            assert_eq!(shown.raw, serde_json::json!(u64::MAX - 5));
            assert_eq!(shown.value, serde_json::json!(u64::MAX - 5));
        }
        assert!(matches!(
            parse(&device, plain, "raw:18446744073709551616"),
            Err(CodecError::OutOfRange(_))
        ));
        assert!(matches!(
            parse(&device, plain, "raw:-1"),
            Err(CodecError::OutOfRange(_))
        ));
        let scaled = device.parameter("scaled").unwrap();
        assert_eq!(
            parse(&device, scaled, "raw:18446744073709551610").unwrap(),
            (u64::MAX - 5).to_le_bytes()
        );
        // Scaled input beyond 2^53 raw steps cannot be converted exactly: refused, not rounded.
        assert!(matches!(
            parse(&device, scaled, "1844674407370955161"),
            Err(CodecError::NotRepresentable(_))
        ));
        assert_eq!(parse(&device, scaled, "1.5").unwrap(), 15u64.to_le_bytes());
    }

    #[test]
    fn decimal_steps_show_as_written() {
        let device = lafert();
        let torque = device.parameter("torque_setpoint").unwrap();
        // 1/100 Arms: raw 35 is 0.35 Arms (35 × 0.01 would be 0.35000000000000003).
        let shown = show(&device, torque, &35i16.to_le_bytes());
        assert_eq!(shown.value, serde_json::json!(0.35));
        assert_eq!(shown.text, "0.35 Arms");
    }

    #[test]
    fn raw_bytes_show_with_units_and_names() {
        let device = lafert();
        let dc = device.parameter("bus_dc_link").unwrap();
        assert_eq!(show(&device, dc, &4950u16.to_le_bytes()).text, "49.50 V");
        let status = device.parameter("drive_status").unwrap();
        assert_eq!(
            show(&device, status, &0x11u16.to_le_bytes()).text,
            "run_velocity|alarm"
        );
        let mode = device.parameter("operation_mode").unwrap();
        assert_eq!(show(&device, mode, &2u16.to_le_bytes()).text, "velocity");
        assert_eq!(show(&device, mode, &9u16.to_le_bytes()).text, "unknown (9)");
    }
}

//! An EDS entry's values (`DefaultValue`, `ParameterValue`, `LowLimit`, `HighLimit`) read for its
//! type, with the leniency rules of `docs/description-format.md` ("How EDS files are read"): every
//! reading other than the plain one, and every value not kept, is a warning naming the value and
//! what was done with it.

use super::dictionary::Text;
use super::lower::{push_once_per_range, EdsEntry};
use super::node_id::{is_float_bit_pattern, parse_value, EdsValue};
use crate::diagnostic::{Diagnostic, Span};
use crate::ir::{self, DataType, Number};

const RULE_VALUE: &str = "eds_values";

/// What an entry's values give its parameter.
pub(super) struct Values {
    /// `DefaultValue`, else `ParameterValue`, and where it is written.
    pub default: Option<(EdsValue, Span)>,
    /// The range of the limits, unless they invert it.
    pub range: Option<ir::Range>,
    /// Where the range is written (a limit).
    pub range_span: Option<Span>,
}

impl EdsEntry {
    /// The values of this entry for type `ty`; problems are warnings, reported once for the
    /// sub-indices of a compact array.
    pub(super) fn values(&self, ty: DataType, diagnostics: &mut Vec<Diagnostic>) -> Values {
        let v = &self.variable;
        let mut found = Vec::new();
        let default = self.value(&v.default, "DefaultValue", ty, &mut found);
        let parameter_value = self.value(&v.parameter_value, "ParameterValue", ty, &mut found);
        let low = constant_limit(self.value(&v.low, "LowLimit", ty, &mut found), &mut found);
        let high = constant_limit(self.value(&v.high, "HighLimit", ty, &mut found), &mut found);
        let range = self.range(ty, low.clone(), high.clone(), &mut found);
        let range_span = range.as_ref().and(low.or(high)).map(|(_, s)| s);
        for d in found {
            push_once_per_range(self, diagnostics, d);
        }
        Values {
            default: default.or(parameter_value),
            range,
            range_span,
        }
    }

    /// The value of `t` (the key `what`) for type `ty`. An empty value is no value; a value the IR
    /// cannot keep or that does not parse is a warning and ignored; a float written as its bit
    /// pattern is a warning naming the value read.
    fn value(
        &self,
        t: &Option<Text>,
        what: &str,
        ty: DataType,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<(EdsValue, Span)> {
        // An empty value (`DefaultValue=`) is no value: nothing is lost by reading it so.
        let t = t.as_ref().filter(|t| !t.value.trim().is_empty())?;
        let span = t.span(self.variable.span.file);
        if let Some(not_kept) = self.not_kept(what, &t.value, &span, ty) {
            diagnostics.push(not_kept);
            return None;
        }
        match parse_value(&t.value, ty) {
            Ok(value) => {
                if let (true, Some(EdsValue::Number(n))) =
                    (is_float_bit_pattern(&t.value, ty), value)
                {
                    let message = format!(
                        "{what} `{}` ({}) is read as its IEEE-754 bit pattern",
                        &*t.value,
                        float_name(ty)
                    );
                    let read = Diagnostic::error(RULE_VALUE, span.clone(), message);
                    diagnostics.push(read.warning().label(format!("read as {n}")));
                }
                value.map(|x| (x, span))
            }
            Err(why) => {
                let message = format!("{what}: {why}");
                let ignored = Diagnostic::error(RULE_VALUE, span, message);
                diagnostics.push(ignored.warning().label("ignored"));
                None
            }
        }
    }

    /// The warning for a value `text` the IR keeps no value of (types that are not numbers).
    fn not_kept(&self, what: &str, text: &str, span: &Span, ty: DataType) -> Option<Diagnostic> {
        let (name, help) = match self.time_type() {
            Some(name) => (
                name.to_owned(),
                format!("drivegen reads a {name} as 6 raw octets (ms after midnight, days since 1984-01-01) and keeps no value of it"),
            ),
            None if matches!(ty, DataType::String(_) | DataType::Octets(_)) => (
                self.type_name(ty),
                "drivegen keeps numeric values only; the generated crate and `eds export` carry none for this object".to_owned(),
            ),
            None => return None,
        };
        let message = format!("{what} `{text}` is not kept ({name})");
        let d = Diagnostic::error(RULE_VALUE, span.clone(), message);
        Some(d.warning().label("ignored").help(help))
    }

    /// How the EDS names the type `ty` it gives this entry (`ty` is the IR's reading).
    fn type_name(&self, ty: DataType) -> String {
        match (self.data_type, self.variable.data_type) {
            (Err(_), Some(code)) => format!("DataType {code:#06X}"),
            (Err(_), None) => "no DataType".into(),
            (Ok(_), Some(0x0009)) => "VISIBLE_STRING".into(),
            (Ok(_), Some(0x000A)) => "OCTET_STRING".into(),
            (Ok(_), Some(0x000B)) => "UNICODE_STRING".into(),
            (Ok(_), Some(0x000F) | None) => "DOMAIN".into(),
            (Ok(_), _) => ty.name().to_owned(),
        }
    }

    /// `TIME_OF_DAY` / `TIME_DIFFERENCE` when the entry has one of these types.
    fn time_type(&self) -> Option<&'static str> {
        match self.variable.data_type {
            Some(0x000C) => Some("TIME_OF_DAY"),
            Some(0x000D) => Some("TIME_DIFFERENCE"),
            _ => None,
        }
    }

    /// The range of the limits; limits that would invert it are dropped with a warning (a signed
    /// type's hex limits `0x00`..`0xFF` read as two's complement give 0..=-1: the vendor means the
    /// whole range, which the type's bounds already give).
    fn range(
        &self,
        ty: DataType,
        low: Option<(Number, Span)>,
        high: Option<(Number, Span)>,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<ir::Range> {
        if let (Some((min, span)), Some((max, _))) = (&low, &high) {
            if min.compare(*max) == Some(std::cmp::Ordering::Greater) {
                let written = [&self.variable.low, &self.variable.high];
                let hex = written.into_iter().flatten().any(|t| is_hex(&t.value));
                let why = if hex && matches!(ty, DataType::Signed(_)) {
                    format!("hex limits of a signed type ({}) read as two's complement give {min}..={max}, an inverted range; read as the whole range of the type", ty.name())
                } else {
                    format!("LowLimit {min} is above HighLimit {max}; the limits are ignored")
                };
                let dropped = Diagnostic::error(RULE_VALUE, span.clone(), why).warning();
                diagnostics.push(dropped.label("range dropped: the type's bounds apply"));
                return None;
            }
        }
        limits(ty, low, high)
    }
}

/// Whether a value is written in `0x` hex.
fn is_hex(text: &str) -> bool {
    let prefix = text.trim_start().get(..2);
    prefix.is_some_and(|p| p.eq_ignore_ascii_case("0x"))
}

/// The CiA 301 name of a float type.
fn float_name(ty: DataType) -> &'static str {
    if ty == DataType::F32 {
        "REAL32"
    } else {
        "REAL64"
    }
}

/// Limits are constants: a `$NODEID` limit is dropped with a warning.
fn constant_limit(
    limit: Option<(EdsValue, Span)>,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<(Number, Span)> {
    match limit? {
        (EdsValue::Number(n), span) => Some((n, span)),
        (EdsValue::NodeIdPlus(_), span) => {
            diagnostics.push(
                Diagnostic::error(RULE_VALUE, span, "a limit relative to `$NODEID` is ignored")
                    .warning(),
            );
            None
        }
    }
}

/// A range from one or both limits; a missing side is the type's bound.
fn limits(
    ty: DataType,
    low: Option<(Number, Span)>,
    high: Option<(Number, Span)>,
) -> Option<ir::Range> {
    if low.is_none() && high.is_none() {
        return None;
    }
    let (min, max) = match ty.integer_bounds() {
        Some((min, max)) => (
            Number::Int(i64::try_from(min).unwrap_or(i64::MIN)),
            Number::Int(i64::try_from(max).unwrap_or(i64::MAX)),
        ),
        None if ty == DataType::F32 => (
            Number::Float(f32::MIN.into()),
            Number::Float(f32::MAX.into()),
        ),
        None => (Number::Float(f64::MIN), Number::Float(f64::MAX)),
    };
    Some(ir::Range {
        min: low.map_or(min, |(n, _)| n),
        max: high.map_or(max, |(n, _)| n),
    })
}

//! One mapped parameter as a DBC signal: where it lies in the payload and how its raw value
//! becomes the engineering value.

use std::fmt::Write as _;

use super::text;
use crate::ir::{DataType, Device, Parameter, Scale};

/// A signal of a message.
#[derive(Debug, Clone)]
pub struct Signal<'d> {
    /// The parameter it carries.
    pub parameter: &'d Parameter,
    /// Its name in the message (the parameter's, made unique within the message).
    pub name: String,
    /// First bit in the payload (little-endian numbering).
    pub start: u32,
    /// Length in bits.
    pub bits: u32,
    factor: f64,
    offset: f64,
    /// Unit of the scaled value; empty when the value is raw.
    unit: String,
    values: Vec<(i64, String)>,
    comment: String,
}

impl<'d> Signal<'d> {
    /// `parameter` at `start`, `bits` long.
    pub fn new(device: &'d Device, parameter: &'d Parameter, start: u32, bits: u32) -> Self {
        let (factor, offset, unit, scale_note) = match &parameter.scale {
            Some(Scale::Fixed(s)) => (
                s.factor.to_f64(),
                s.offset.to_f64(),
                parameter.unit.clone().unwrap_or_default(),
                None,
            ),
            Some(Scale::Runtime { expr, .. }) => (
                1.0,
                0.0,
                String::new(),
                Some(format!(
                    " Raw value: the drive scales it at run time ({expr}{}).",
                    parameter
                        .unit
                        .as_deref()
                        .map(|u| format!(" gives {u}"))
                        .unwrap_or_default()
                )),
            ),
            None => (1.0, 0.0, parameter.unit.clone().unwrap_or_default(), None),
        };
        let values = parameter
            .enumeration
            .as_deref()
            .and_then(|name| device.enumeration(name))
            .map(|e| e.values.iter().map(|v| (v.value, v.name.clone())).collect())
            .unwrap_or_default();
        let comment = format!(
            "{}{}",
            parameter.doc.as_deref().unwrap_or(&parameter.name),
            scale_note.unwrap_or_default()
        );
        Self {
            parameter,
            name: text::identifier(&parameter.name),
            start,
            bits,
            factor,
            offset,
            unit,
            values,
            comment,
        }
    }

    /// Signed integers and floats (whose sign bit DBC readers take from IEEE 754).
    fn signed(&self) -> bool {
        matches!(
            self.parameter.data_type,
            DataType::Signed(_) | DataType::F32 | DataType::F64
        )
    }

    /// The DBC value type of a float signal: 1 single, 2 double; `None` for an integer.
    pub fn float_type(&self) -> Option<u8> {
        match self.parameter.data_type {
            DataType::F32 => Some(1),
            DataType::F64 => Some(2),
            _ => None,
        }
    }

    /// The engineering range: the described raw range, else the type's, through the scale;
    /// `(0, 0)` (no range, in DBC) for a float without a described range.
    fn range(&self) -> (f64, f64) {
        let raw = match (
            &self.parameter.range,
            self.parameter.data_type.integer_bounds(),
        ) {
            (Some(r), _) => (r.min.as_f64(), r.max.as_f64()),
            (None, Some((min, max))) => (min as f64, max as f64),
            (None, None) => return (0.0, 0.0),
        };
        let ends = (
            raw.0 * self.factor + self.offset,
            raw.1 * self.factor + self.offset,
        );
        (ends.0.min(ends.1), ends.0.max(ends.1))
    }

    /// ` SG_ name : start|bits@1+ (factor,offset) [min|max] "unit" receivers`.
    pub fn write_definition(&self, out: &mut String, receivers: &str) {
        let (min, max) = self.range();
        let _ = writeln!(
            out,
            " SG_ {} : {}|{}@1{} ({},{}) [{}|{}] \"{}\" {receivers}",
            self.name,
            self.start,
            self.bits,
            if self.signed() { '-' } else { '+' },
            text::number(self.factor),
            text::number(self.offset),
            text::number(min),
            text::number(max),
            text::string(&self.unit),
        );
    }

    /// `CM_ SG_ id name "doc";`.
    pub fn write_comment(&self, out: &mut String, id: u32) {
        let _ = writeln!(
            out,
            "CM_ SG_ {id} {} \"{}\";",
            self.name,
            text::string(&self.comment)
        );
    }

    /// `VAL_ id name 1 "a" 2 "b" ;` for an enumeration.
    pub fn write_value_table(&self, out: &mut String, id: u32) {
        if self.values.is_empty() {
            return;
        }
        let _ = write!(out, "VAL_ {id} {}", self.name);
        for (value, name) in &self.values {
            let _ = write!(out, " {value} \"{}\"", text::string(name));
        }
        out.push_str(" ;\n");
    }
}

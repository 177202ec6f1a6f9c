//! How a parameter looks in OPC UA: its data type, where its value comes from in the poller's
//! payload, and how a written `Variant` becomes the set message `drivegen write` checks.
//!
//! Scaled values are Doubles in engineering units; integers, booleans and floats keep their
//! type; enums and flags are their raw integer (an enum's names are its `EnumValues`); a value
//! whose scale is computed at run time is its raw integer too (its engineering value is not
//! known without the other parameters).

use drivegen::ir::{DataType, Device, Parameter, Scale};
use opcua::types::{ByteString, DataTypeId, StatusCode, Variant};

/// An integer type of OPC UA.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Int {
    /// `SByte`.
    I8,
    /// `Int16`.
    I16,
    /// `Int32`.
    I32,
    /// `Int64`.
    I64,
    /// `Byte`.
    U8,
    /// `UInt16`.
    U16,
    /// `UInt32`.
    U32,
    /// `UInt64`.
    U64,
}

/// A parameter's OPC UA shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A scaled value or an `f64`: `Double`, from the payload's `value`.
    Double,
    /// An unscaled `f32`: `Float`, from `value`.
    Float,
    /// An integer, from the payload's `raw`; written as a value, or as raw when `raw`.
    Integer {
        /// Its type.
        int: Int,
        /// Enums, flags and run-time scales: written as `{"raw": n}`.
        raw: bool,
    },
    /// `Boolean`, from `raw`.
    Bool,
    /// `String`, from `value`.
    Text,
    /// `ByteString`, from `raw` (never written through the gateway).
    Bytes,
}

impl Kind {
    /// The shape of `parameter`.
    pub fn of(parameter: &Parameter) -> Self {
        let symbolic = parameter.enumeration.is_some() || parameter.flags.is_some();
        let runtime = matches!(parameter.scale, Some(Scale::Runtime { .. }));
        let scaled = matches!(
            parameter.scale,
            Some(Scale::Fixed(scale)) if scale != drivebus::Scale::IDENTITY
        );
        match parameter.data_type {
            DataType::Bool => Kind::Bool,
            DataType::String(_) => Kind::Text,
            DataType::Octets(_) => Kind::Bytes,
            DataType::F32 if !scaled => Kind::Float,
            DataType::F32 | DataType::F64 => Kind::Double,
            DataType::Unsigned(_) | DataType::Signed(_) if scaled && !symbolic => Kind::Double,
            DataType::Unsigned(width) => Kind::Integer {
                int: match width {
                    1 => Int::U8,
                    2 => Int::U16,
                    3 | 4 => Int::U32,
                    _ => Int::U64,
                },
                raw: symbolic || runtime,
            },
            DataType::Signed(width) => Kind::Integer {
                int: match width {
                    1 => Int::I8,
                    2 => Int::I16,
                    3 | 4 => Int::I32,
                    _ => Int::I64,
                },
                raw: symbolic || runtime,
            },
        }
    }

    /// Its OPC UA data type.
    pub fn data_type(self) -> DataTypeId {
        match self {
            Kind::Double => DataTypeId::Double,
            Kind::Float => DataTypeId::Float,
            Kind::Bool => DataTypeId::Boolean,
            Kind::Text => DataTypeId::String,
            Kind::Bytes => DataTypeId::ByteString,
            Kind::Integer { int, .. } => match int {
                Int::I8 => DataTypeId::SByte,
                Int::I16 => DataTypeId::Int16,
                Int::I32 => DataTypeId::Int32,
                Int::I64 => DataTypeId::Int64,
                Int::U8 => DataTypeId::Byte,
                Int::U16 => DataTypeId::UInt16,
                Int::U32 => DataTypeId::UInt32,
                Int::U64 => DataTypeId::UInt64,
            },
        }
    }

    /// Whether values of this shape carry the description's unit and range (engineering
    /// values, not raw integers or names).
    pub fn is_engineering(self) -> bool {
        matches!(
            self,
            Kind::Double | Kind::Float | Kind::Integer { raw: false, .. }
        )
    }

    /// The value of a poller payload (`{"value": ..., "raw": ...}`), or `None` when it does
    /// not fit the shape (a value that did not decode).
    pub fn variant(self, payload: &serde_json::Value) -> Option<Variant> {
        let value = payload.get("value");
        let raw = payload.get("raw");
        let int = || {
            let raw = raw?;
            raw.as_i64()
                .map(i128::from)
                .or(raw.as_u64().map(i128::from))
        };
        Some(match self {
            Kind::Double => Variant::Double(value?.as_f64()?),
            Kind::Float => Variant::Float(value?.as_f64()? as f32),
            Kind::Bool => Variant::Boolean(int()? != 0),
            Kind::Text => Variant::String(value?.as_str()?.into()),
            Kind::Bytes => {
                let bytes: Option<Vec<u8>> = raw?
                    .as_array()?
                    .iter()
                    .map(|b| b.as_u64().and_then(|b| u8::try_from(b).ok()))
                    .collect();
                Variant::ByteString(ByteString::from(bytes?))
            }
            Kind::Integer { int: kind, .. } => integer(kind, int()?)?,
        })
    }

    /// The set message of a written value: `{"value": ...}` or `{"raw": ...}`, the words an
    /// MQTT client would use. A value of another type is refused with `BadTypeMismatch`.
    pub fn set_message(self, written: Option<&Variant>) -> Result<serde_json::Value, StatusCode> {
        let mismatch = StatusCode::BadTypeMismatch;
        let written = written.ok_or(mismatch)?;
        let message = match (self, written) {
            (Kind::Double, Variant::Double(x)) => number(*x)?,
            // Through its decimal text, so 0.1f32 is written as 0.1, not 0.10000000149.
            (Kind::Float, Variant::Float(x)) => {
                number(x.to_string().parse().map_err(|_| mismatch)?)?
            }
            (Kind::Bool, Variant::Boolean(b)) => serde_json::json!({ "value": b.to_string() }),
            (Kind::Text, Variant::String(s)) => {
                serde_json::json!({ "value": s.as_ref() })
            }
            (Kind::Integer { int, raw }, written) => {
                let value = integer_of(int, written).ok_or(mismatch)?;
                let value = serde_json::Value::from(value);
                match raw {
                    true => serde_json::json!({ "raw": value }),
                    false => serde_json::json!({ "value": value }),
                }
            }
            (Kind::Bytes, _) => return Err(StatusCode::BadNotWritable),
            _ => return Err(mismatch),
        };
        Ok(message)
    }
}

/// `{"value": x}`; NaN and the infinities are out of every range.
fn number(x: f64) -> Result<serde_json::Value, StatusCode> {
    match x.is_finite() {
        true => Ok(serde_json::json!({ "value": x })),
        false => Err(StatusCode::BadOutOfRange),
    }
}

/// `value` as a `Variant` of `kind`, if it fits.
fn integer(kind: Int, value: i128) -> Option<Variant> {
    Some(match kind {
        Int::I8 => Variant::SByte(value.try_into().ok()?),
        Int::I16 => Variant::Int16(value.try_into().ok()?),
        Int::I32 => Variant::Int32(value.try_into().ok()?),
        Int::I64 => Variant::Int64(value.try_into().ok()?),
        Int::U8 => Variant::Byte(value.try_into().ok()?),
        Int::U16 => Variant::UInt16(value.try_into().ok()?),
        Int::U32 => Variant::UInt32(value.try_into().ok()?),
        Int::U64 => Variant::UInt64(value.try_into().ok()?),
    })
}

/// The integer a written `Variant` holds, when it is of exactly `kind`'s type (as a JSON number:
/// i64 or u64).
fn integer_of(kind: Int, written: &Variant) -> Option<serde_json::Number> {
    Some(match (kind, written) {
        (Int::I8, Variant::SByte(v)) => i64::from(*v).into(),
        (Int::I16, Variant::Int16(v)) => i64::from(*v).into(),
        (Int::I32, Variant::Int32(v)) => i64::from(*v).into(),
        (Int::I64, Variant::Int64(v)) => (*v).into(),
        (Int::U8, Variant::Byte(v)) => u64::from(*v).into(),
        (Int::U16, Variant::UInt16(v)) => u64::from(*v).into(),
        (Int::U32, Variant::UInt32(v)) => u64::from(*v).into(),
        (Int::U64, Variant::UInt64(v)) => (*v).into(),
        _ => return None,
    })
}

/// The engineering range of `parameter` (its raw range through its fixed scale), when it has
/// one and its values are engineering values.
pub fn eu_range(parameter: &Parameter) -> Option<(f64, f64)> {
    let range = parameter.range.as_ref()?;
    let scale = match &parameter.scale {
        None => drivebus::Scale::IDENTITY,
        Some(Scale::Fixed(scale)) => *scale,
        Some(Scale::Runtime { .. }) => return None,
    };
    let (a, b) = (
        scale.to_engineering(range.min.as_f64()),
        scale.to_engineering(range.max.as_f64()),
    );
    // A negative factor turns the range round.
    Some((a.min(b), a.max(b)))
}

/// An enum's values and names, for `EnumValues`.
pub fn enum_values<'d>(device: &'d Device, parameter: &Parameter) -> Vec<(i64, &'d str)> {
    parameter
        .enumeration
        .as_deref()
        .and_then(|name| device.enumeration(name))
        .map(|e| {
            e.values
                .iter()
                .map(|v| (v.value, v.name.as_str()))
                .collect()
        })
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn payloads_become_variants_of_the_shape() {
        let payload = serde_json::json!({ "value": 49.5, "raw": 495 });
        assert_eq!(Kind::Double.variant(&payload), Some(Variant::Double(49.5)));
        let int = Kind::Integer {
            int: Int::U16,
            raw: false,
        };
        assert_eq!(int.variant(&payload), Some(Variant::UInt16(495)));
        let small = Kind::Integer {
            int: Int::U8,
            raw: true,
        };
        assert_eq!(small.variant(&payload), None, "495 is not a Byte");
        let name = serde_json::json!({ "value": "velocity", "raw": 3 });
        assert_eq!(small.variant(&name), Some(Variant::Byte(3)));
        assert_eq!(
            Kind::Double.variant(&serde_json::json!({ "value": null })),
            None
        );
    }

    #[test]
    fn writes_become_set_messages_or_a_type_mismatch() {
        let message = Kind::Double.set_message(Some(&Variant::Double(1500.0)));
        assert_eq!(message, Ok(serde_json::json!({ "value": 1500.0 })));
        let enumerated = Kind::Integer {
            int: Int::I16,
            raw: true,
        };
        let message = enumerated.set_message(Some(&Variant::Int16(-3)));
        assert_eq!(message, Ok(serde_json::json!({ "raw": -3 })));
        for wrong in [
            Variant::Int32(3),
            Variant::from("fast"),
            Variant::Double(3.0),
        ] {
            assert_eq!(
                enumerated.set_message(Some(&wrong)),
                Err(StatusCode::BadTypeMismatch)
            );
        }
        assert_eq!(
            Kind::Double.set_message(Some(&Variant::Double(f64::NAN))),
            Err(StatusCode::BadOutOfRange)
        );
        let float = Kind::Float.set_message(Some(&Variant::Float(0.1)));
        assert_eq!(float, Ok(serde_json::json!({ "value": 0.1 })));
        assert_eq!(
            Kind::Double.set_message(None),
            Err(StatusCode::BadTypeMismatch)
        );
    }
}

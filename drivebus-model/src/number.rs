//! Raw numbers of defaults, ranges and allowed values as a description writes them: exact
//! integers, or floats for float types. The generator's model and the run-time interpreter share
//! them.

use core::cmp::Ordering;
use core::fmt;

use crate::RawValue;

/// A raw value as written in a description.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Number {
    /// An integer.
    Int(i64),
    /// A float (only for `f32`/`f64` parameters).
    Float(f64),
}

impl Number {
    /// The value as `f64`.
    pub fn as_f64(self) -> f64 {
        match self {
            Number::Int(i) => i as f64,
            Number::Float(f) => f,
        }
    }
    /// How two raw values compare: integers exactly (as floats, neighbours near ±2^63 are
    /// equal), anything else as floats; `None` with NaN.
    pub fn compare(self, other: Number) -> Option<Ordering> {
        match (self, other) {
            (Number::Int(a), Number::Int(b)) => Some(a.cmp(&b)),
            _ => self.as_f64().partial_cmp(&other.as_f64()),
        }
    }

    /// How a raw value read or typed at run time compares with this number: integers exactly,
    /// anything else as floats; `None` with NaN.
    pub fn compare_raw(self, raw: RawValue) -> Option<Ordering> {
        match (raw, self) {
            (RawValue::Int(i), Number::Int(n)) => Some(i.cmp(&i128::from(n))),
            _ => raw.as_f64().partial_cmp(&self.as_f64()),
        }
    }

    /// The value as an integer, if it is one.
    pub fn as_int(self) -> Option<i64> {
        match self {
            Number::Int(i) => Some(i),
            Number::Float(_) => None,
        }
    }
}

impl From<Number> for RawValue {
    fn from(number: Number) -> RawValue {
        match number {
            Number::Int(i) => RawValue::Int(i.into()),
            Number::Float(f) => RawValue::Float(f),
        }
    }
}

/// As written in diagnostics, docs and EDS files: a float in its shortest exact form, with an
/// exponent when it is very large or small (`1e300`, not 301 digits) and a `.0` when integral,
/// so that it reads back as the same float.
impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Number::Int(i) => write!(f, "{i}"),
            Number::Float(x) => write!(f, "{x:?}"),
        }
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for Number {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Number::Int(i) => serializer.serialize_i64(*i),
            Number::Float(f) => serializer.serialize_f64(*f),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_integers_compare_exactly_beyond_float_precision() {
        let big = RawValue::Int(i128::from(i64::MAX));
        assert_eq!(
            Number::Int(i64::MAX - 1).compare_raw(big),
            Some(Ordering::Greater)
        );
        assert_eq!(
            Number::Int(1).compare_raw(RawValue::Float(1.5)),
            Some(Ordering::Greater)
        );
        assert_eq!(Number::Int(1).compare_raw(RawValue::Float(f64::NAN)), None);
        let beyond_i64 = RawValue::Int(i128::from(u64::MAX));
        assert_eq!(
            Number::Int(i64::MAX).compare_raw(beyond_i64),
            Some(Ordering::Greater)
        );
    }
}

//! A raw value as the command line handles it: integers stay exact. An `f64` holds 53 bits, a
//! `u64` or `i64` raw value 64, so `raw:18446744073709551610` must not pass through a float.

use core::fmt;

#[cfg(feature = "alloc")]
use crate::DataType;

/// A raw value: an exact integer, or a float for float parameters and scaled input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RawValue {
    /// An integer, exact over the whole range of every integer type.
    Int(i128),
    /// A float.
    Float(f64),
}

impl RawValue {
    /// The value as a float (rounded for integers beyond 2^53).
    pub fn as_f64(self) -> f64 {
        match self {
            RawValue::Int(i) => i as f64,
            RawValue::Float(f) => f,
        }
    }

    #[cfg(feature = "alloc")]
    /// The value `bytes` hold as `data_type`: an integer exactly, a float as a float; `None`
    /// for text and octets, or too few bytes.
    pub fn of(data_type: DataType, bytes: &[u8]) -> Option<RawValue> {
        match crate::raw::to_int(data_type, bytes) {
            Some(int) => Some(RawValue::Int(int)),
            None => crate::raw::to_f64(data_type, bytes).map(RawValue::Float),
        }
    }
}

impl fmt::Display for RawValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RawValue::Int(i) => write!(f, "{i}"),
            RawValue::Float(x) => write!(f, "{x}"),
        }
    }
}

#[cfg(all(test, feature = "alloc"))]
mod tests {
    use super::*;

    #[test]
    fn bytes_read_as_exact_integers_or_floats() {
        let max = u64::MAX.to_le_bytes();
        assert_eq!(
            RawValue::of(DataType::Unsigned(8), &max),
            Some(RawValue::Int(i128::from(u64::MAX)))
        );
        assert_eq!(
            RawValue::of(DataType::F32, &1.5f32.to_le_bytes()),
            Some(RawValue::Float(1.5))
        );
        assert_eq!(RawValue::of(DataType::String(4), b"abcd"), None);
    }
}

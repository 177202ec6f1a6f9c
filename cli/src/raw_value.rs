//! A raw value as the command line handles it: integers stay exact. An `f64` holds 53 bits, a
//! `u64` or `i64` raw value 64, so `raw:18446744073709551610` must not pass through a float.

use std::cmp::Ordering;
use std::fmt;

use drivegen::ir::Number;

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

    /// How the value compares with a described number (a range bound or an allowed value);
    /// `None` for NaN.
    pub fn compare(self, number: Number) -> Option<Ordering> {
        match (self, number) {
            (RawValue::Int(i), Number::Int(n)) => Some(i.cmp(&i128::from(n))),
            _ => self.as_f64().partial_cmp(&number.as_f64()),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers_compare_exactly_beyond_float_precision() {
        let big = RawValue::Int(i128::from(i64::MAX));
        assert_eq!(
            big.compare(Number::Int(i64::MAX - 1)),
            Some(Ordering::Greater)
        );
        assert_eq!(
            RawValue::Float(1.5).compare(Number::Int(1)),
            Some(Ordering::Greater)
        );
        assert_eq!(RawValue::Float(f64::NAN).compare(Number::Int(1)), None);
    }
}

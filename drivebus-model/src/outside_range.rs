//! A raw value outside the range it must lie in, exactly.

use core::fmt;

use crate::RawValue;

/// A raw value and the inclusive range it lies outside, all exact (an integer as an integer).
///
/// The three share one tag, so that the error carrying them (`drivebus::ValueError::OutOfRange`)
/// stays small: three [`RawValue`]s would take 96 bytes, this takes 64.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OutsideRange {
    /// An integer raw value and integer ends.
    Int {
        /// The raw value asked for.
        raw: i128,
        /// Smallest allowed raw value.
        min: i128,
        /// Largest allowed raw value.
        max: i128,
    },
    /// A float raw value, or float ends.
    Float {
        /// The raw value asked for.
        raw: f64,
        /// Smallest allowed raw value.
        min: f64,
        /// Largest allowed raw value.
        max: f64,
    },
}

impl OutsideRange {
    /// `raw` outside `min..=max`; floats throughout if any of the three is a float.
    pub fn new(raw: RawValue, min: RawValue, max: RawValue) -> Self {
        match (raw, min, max) {
            (RawValue::Int(raw), RawValue::Int(min), RawValue::Int(max)) => {
                Self::Int { raw, min, max }
            }
            (raw, min, max) => Self::Float {
                raw: raw.as_f64(),
                min: min.as_f64(),
                max: max.as_f64(),
            },
        }
    }

    /// The raw value asked for.
    pub fn raw(&self) -> RawValue {
        match *self {
            Self::Int { raw, .. } => RawValue::Int(raw),
            Self::Float { raw, .. } => RawValue::Float(raw),
        }
    }

    /// Smallest allowed raw value.
    pub fn min(&self) -> RawValue {
        match *self {
            Self::Int { min, .. } => RawValue::Int(min),
            Self::Float { min, .. } => RawValue::Float(min),
        }
    }

    /// Largest allowed raw value.
    pub fn max(&self) -> RawValue {
        match *self {
            Self::Int { max, .. } => RawValue::Int(max),
            Self::Float { max, .. } => RawValue::Float(max),
        }
    }
}

impl fmt::Display for OutsideRange {
    /// `raw value 9 is outside the allowed range 1..=8`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "raw value {} is outside the allowed range {}..={}",
            self.raw(),
            self.min(),
            self.max()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_stay_exact_and_of_their_kind() {
        let big = (1i128 << 53) + 1;
        let outside = OutsideRange::new(RawValue::Int(big), RawValue::Int(0), RawValue::Int(8));
        assert_eq!(
            outside,
            OutsideRange::Int {
                raw: big,
                min: 0,
                max: 8
            }
        );
        assert_eq!(outside.raw(), RawValue::Int(big));
        assert_eq!(
            std::format!("{outside}"),
            "raw value 9007199254740993 is outside the allowed range 0..=8"
        );
        let mixed = OutsideRange::new(RawValue::Float(2.5), RawValue::Int(0), RawValue::Int(1));
        assert_eq!(mixed.max(), RawValue::Float(1.0));
        assert!(core::mem::size_of::<OutsideRange>() <= 64);
    }
}

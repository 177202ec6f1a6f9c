//! The raw values a [`Scale`](crate::Scale) converts: integers, floats and booleans, each
//! convertible to and from `f64` without silent rounding.

/// A numeric raw value, convertible to and from `f64` for scaling and range checks.
pub trait Scalable: Copy + PartialOrd {
    /// Whether the type holds only whole numbers (scaled writes must then land on a step).
    const IS_INTEGER: bool;
    /// The value as `f64` (exact for every integer up to 2^53 and for floats).
    fn to_f64(self) -> f64;
    /// The value from an `f64` if it is integral (for integer types) and in the type's range.
    fn from_f64(value: f64) -> Option<Self>;
}

/// `x` rounded half away from zero; `core` has no `f64::round` without `std`.
pub fn round(x: f64) -> f64 {
    // Beyond 2^52 every f64 is already a whole number (and NaN/inf pass through).
    if x.is_nan() || x.abs() >= 4_503_599_627_370_496.0 {
        return x;
    }
    let t = x as i64 as f64;
    let diff = x - t;
    if diff >= 0.5 {
        t + 1.0
    } else if diff <= -0.5 {
        t - 1.0
    } else {
        t
    }
}

fn is_whole(x: f64) -> bool {
    round(x) == x
}

macro_rules! integer_scalable {
    ($($ty:ty),* $(,)?) => {$(
        impl Scalable for $ty {
            const IS_INTEGER: bool = true;
            fn to_f64(self) -> f64 {
                self as f64
            }
            fn from_f64(value: f64) -> Option<Self> {
                let in_range = value >= <$ty>::MIN as f64 && value <= <$ty>::MAX as f64;
                (is_whole(value) && in_range).then(|| value as $ty)
            }
        }
    )*};
}

integer_scalable!(u8, u16, u32, u64, i8, i16, i32, i64);

macro_rules! float_scalable {
    ($($ty:ty),*) => {$(
        impl Scalable for $ty {
            const IS_INTEGER: bool = false;
            fn to_f64(self) -> f64 {
                self as f64
            }
            /// `None` where the value is infinite in this width (an `f32` beyond `f32::MAX`):
            /// it would reach the drive as infinity.
            fn from_f64(value: f64) -> Option<Self> {
                let narrowed = value as $ty;
                narrowed.is_finite().then_some(narrowed)
            }
        }
    )*};
}

float_scalable!(f32, f64);

/// CiA 301 BOOLEAN as the numbers 0 and 1 (`false < true`), so that the range and allowed values
/// a description gives a boolean are checked like any other parameter's.
impl Scalable for bool {
    const IS_INTEGER: bool = true;
    fn to_f64(self) -> f64 {
        f64::from(u8::from(self))
    }
    fn from_f64(value: f64) -> Option<Self> {
        match value {
            0.0 => Some(false),
            1.0 => Some(true),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_is_half_away_from_zero() {
        assert_eq!(round(2.5), 3.0);
        assert_eq!(round(-2.5), -3.0);
        assert_eq!(round(2.4999), 2.0);
        assert_eq!(round(1e300), 1e300);
    }

    #[test]
    fn from_f64_rejects_fractions_and_overflow() {
        assert_eq!(u16::from_f64(4950.0), Some(4950));
        assert_eq!(u16::from_f64(49.5), None);
        assert_eq!(u16::from_f64(70000.0), None);
        assert_eq!(i16::from_f64(-3000.0), Some(-3000));
    }
}

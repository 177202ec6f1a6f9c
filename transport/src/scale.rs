//! Exact scaling between raw register values and engineering values.
//!
//! A scale is `engineering = raw × factor + offset` with `factor` and `offset` exact rationals, so a
//! description's `1/100` stays exact; conversion to `f64` happens once, at the edge.

use crate::error::ValueError;
use crate::value::Numeric;

/// An exact rational number `num / den` with `den > 0`, kept in lowest terms.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Ratio {
    num: i64,
    den: i64,
}

const fn gcd(mut a: i128, mut b: i128) -> i128 {
    while b != 0 {
        let t = a % b;
        a = b;
        b = t;
    }
    if a < 0 {
        -a
    } else {
        a
    }
}

impl Ratio {
    /// Zero.
    pub const ZERO: Ratio = Ratio { num: 0, den: 1 };
    /// One.
    pub const ONE: Ratio = Ratio { num: 1, den: 1 };

    /// `num / den` in lowest terms, or `None` if `den` is zero or the result overflows `i64`.
    pub const fn new(num: i64, den: i64) -> Option<Ratio> {
        Self::from_wide(num as i128, den as i128)
    }

    /// An integer.
    pub const fn int(value: i64) -> Ratio {
        Ratio { num: value, den: 1 }
    }

    const fn from_wide(num: i128, den: i128) -> Option<Ratio> {
        if den == 0 {
            return None;
        }
        let sign = if den < 0 { -1 } else { 1 };
        let g = gcd(num, den);
        let (num, den) = (sign * num / g, sign * den / g);
        if num < i64::MIN as i128 || num > i64::MAX as i128 || den > i64::MAX as i128 {
            return None;
        }
        Some(Ratio {
            num: num as i64,
            den: den as i64,
        })
    }

    /// Numerator (sign carrier).
    pub const fn numerator(self) -> i64 {
        self.num
    }
    /// Denominator (always positive).
    pub const fn denominator(self) -> i64 {
        self.den
    }

    /// `self + rhs`, `None` on overflow.
    pub fn checked_add(self, rhs: Ratio) -> Option<Ratio> {
        let (a, b, c, d) = self.wide(rhs);
        Self::from_wide(a * d + c * b, b * d)
    }
    /// `self - rhs`, `None` on overflow.
    pub fn checked_sub(self, rhs: Ratio) -> Option<Ratio> {
        self.checked_add(Ratio {
            num: rhs.num.checked_neg()?,
            den: rhs.den,
        })
    }
    /// `self × rhs`, `None` on overflow.
    pub fn checked_mul(self, rhs: Ratio) -> Option<Ratio> {
        let (a, b, c, d) = self.wide(rhs);
        Self::from_wide(a * c, b * d)
    }
    /// `self ÷ rhs`, `None` on division by zero or overflow.
    pub fn checked_div(self, rhs: Ratio) -> Option<Ratio> {
        let (a, b, c, d) = self.wide(rhs);
        Self::from_wide(a * d, b * c)
    }

    fn wide(self, rhs: Ratio) -> (i128, i128, i128, i128) {
        (
            self.num as i128,
            self.den as i128,
            rhs.num as i128,
            rhs.den as i128,
        )
    }

    /// An integer raw value as a ratio, `None` if it is not a whole number within `i64`.
    pub fn from_raw<R: Numeric>(raw: R) -> Option<Ratio> {
        let value = raw.to_f64();
        let whole = i64::from_f64(value)?;
        // `to_f64` is exact only up to 2^53; refuse larger values rather than use a rounded one.
        (value.abs() < 9_007_199_254_740_992.0).then_some(Ratio::int(whole))
    }

    /// The nearest `f64`.
    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }
}

/// `engineering = raw × factor + offset`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Scale {
    /// Multiplier from raw to engineering units.
    pub factor: Ratio,
    /// Added after multiplying.
    pub offset: Ratio,
}

impl Scale {
    /// The identity scale (raw value is the engineering value).
    pub const IDENTITY: Scale = Scale {
        factor: Ratio::ONE,
        offset: Ratio::ZERO,
    };

    /// A scale with the given factor and offset, from the generator's exact fractions.
    pub const fn fixed(num: i64, den: i64, offset_num: i64, offset_den: i64) -> Scale {
        match (Ratio::new(num, den), Ratio::new(offset_num, offset_den)) {
            (Some(factor), Some(offset)) => Scale { factor, offset },
            _ => panic!("the generator emits only valid scales"),
        }
    }

    /// A scale with the given factor and no offset.
    pub const fn factor(factor: Ratio) -> Scale {
        Scale {
            factor,
            offset: Ratio::ZERO,
        }
    }

    /// Engineering value of a raw value.
    pub fn to_engineering<R: Numeric>(self, raw: R) -> f64 {
        raw.to_f64() * self.factor.to_f64() + self.offset.to_f64()
    }

    /// Raw value of an engineering value; refuses values that would have to be rounded or do not
    /// fit the raw type, so nothing is silently changed on its way to the drive.
    pub fn to_raw<R: Numeric>(self, parameter: &'static str, value: f64) -> Result<R, ValueError> {
        if !value.is_finite() {
            return Err(ValueError::Overflow { parameter });
        }
        let exact = (value - self.offset.to_f64()) / self.factor.to_f64();
        if !R::IS_INTEGER {
            return R::from_f64(exact).ok_or(ValueError::Overflow { parameter });
        }
        let nearest = crate::value::round(exact);
        // A relative tolerance absorbs decimal→binary noise (49.5 / 0.01) but no real rounding.
        let tolerance = 1e-9 * nearest.abs().max(1.0);
        if (exact - nearest).abs() > tolerance {
            let step = self.factor.to_f64().abs();
            return Err(ValueError::NotRepresentable {
                parameter,
                value,
                step,
            });
        }
        R::from_f64(nearest).ok_or(ValueError::Overflow { parameter })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratios_are_reduced_and_sign_normalised() {
        assert_eq!(Ratio::new(50, -100), Ratio::new(-1, 2));
        assert_eq!(Ratio::new(1, 0), None);
    }

    #[test]
    fn kinco_speed_factor_is_exact() {
        // rpm = DEC × 1875 / (512 × 10000) for a 10000-count encoder.
        let f =
            Ratio::int(1875).checked_div(Ratio::int(512).checked_mul(Ratio::int(10_000)).unwrap());
        assert_eq!(f, Ratio::new(3, 8192));
        let scale = Scale::factor(f.unwrap());
        assert_eq!(scale.to_raw::<i32>("target_speed", 1500.0), Ok(4_096_000));
    }

    #[test]
    fn volts_round_trip_through_hundredths() {
        let scale = Scale::factor(Ratio::new(1, 100).unwrap());
        assert_eq!(scale.to_engineering(4950u16), 49.5);
        assert_eq!(scale.to_raw::<u16>("bus_dc_link", 49.5), Ok(4950));
    }

    #[test]
    fn values_between_steps_are_refused_not_rounded() {
        let scale = Scale::factor(Ratio::new(1, 10).unwrap());
        assert!(matches!(
            scale.to_raw::<i16>("motor_temperature", 35.55),
            Err(ValueError::NotRepresentable { .. })
        ));
    }

    #[test]
    fn offsets_apply_after_the_factor() {
        let scale = Scale {
            factor: Ratio::new(1, 10).unwrap(),
            offset: Ratio::int(-40),
        };
        assert_eq!(scale.to_engineering(400u16), 0.0);
        assert_eq!(scale.to_raw::<u16>("t", -40.0), Ok(0));
    }

    #[test]
    fn raw_overflow_is_an_error() {
        assert_eq!(
            Scale::IDENTITY.to_raw::<u8>("x", 300.0),
            Err(ValueError::Overflow { parameter: "x" })
        );
    }
}

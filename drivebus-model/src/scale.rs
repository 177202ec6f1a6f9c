//! Exact scaling between raw register values and engineering values.
//!
//! A scale is `engineering = raw × factor + offset` with `factor` and `offset` exact rationals, so a
//! description's `1/100` stays exact; conversion to `f64` happens once, at the edge.

use core::fmt;

use crate::scalable::{round, Scalable};

/// Below this magnitude every integer is exact in `f64` (2^53).
pub const EXACT_INTEGERS: f64 = 9_007_199_254_740_992.0;

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
    pub fn from_raw<R: Scalable>(raw: R) -> Option<Ratio> {
        let value = raw.to_f64();
        let whole = i64::from_f64(value)?;
        // `to_f64` is exact only up to 2^53; refuse larger values rather than use a rounded one.
        (value.abs() < EXACT_INTEGERS).then_some(Ratio::int(whole))
    }

    /// The nearest `f64`.
    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }

    /// Parses an exact number as descriptions write it: an integer (`-40`), a decimal (`0.1`,
    /// never rounded) or a quotient of those (`1/100`, `2.5/0.5`). `None` for anything else,
    /// a zero denominator, or a value beyond `i64`.
    pub fn parse(text: &str) -> Option<Ratio> {
        match text.split_once('/') {
            None => Self::parse_decimal(text),
            Some((num, den)) => Self::parse_decimal(num)?.checked_div(Self::parse_decimal(den)?),
        }
    }

    /// Parses `12` or `-0.25` exactly: the digits after the point are the numerator over a power
    /// of ten.
    pub fn parse_decimal(text: &str) -> Option<Ratio> {
        let text = text.trim();
        let (negative, digits) = match text.strip_prefix('-') {
            Some(rest) => (true, rest),
            None => (false, text),
        };
        let (whole, fraction) = digits.split_once('.').unwrap_or((digits, ""));
        if whole.is_empty() || fraction.len() > 18 {
            return None;
        }
        let mut numerator: i64 = 0;
        for byte in whole.bytes().chain(fraction.bytes()) {
            let digit = byte.is_ascii_digit().then(|| i64::from(byte - b'0'))?;
            numerator = numerator.checked_mul(10)?.checked_add(digit)?;
        }
        let denominator = 10i64.checked_pow(fraction.len() as u32)?;
        Ratio::new(if negative { -numerator } else { numerator }, denominator)
    }
}

/// `{ "numerator": n, "denominator": d }`, the IR JSON's spelling of an exact number.
#[cfg(feature = "serde")]
impl serde::Serialize for Ratio {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut out = serializer.serialize_struct("Ratio", 2)?;
        out.serialize_field("numerator", &self.num)?;
        out.serialize_field("denominator", &self.den)?;
        out.end()
    }
}

/// The factor's `numerator` and `denominator` beside an `offset` ratio, as the IR JSON has it.
#[cfg(feature = "serde")]
impl serde::Serialize for Scale {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut out = serializer.serialize_struct("Scale", 3)?;
        out.serialize_field("numerator", &self.factor.num)?;
        out.serialize_field("denominator", &self.factor.den)?;
        out.serialize_field("offset", &self.offset)?;
        out.end()
    }
}

/// Why an engineering value has no raw value under a scale; nothing is rounded or truncated.
/// The caller knows which value of which parameter it asked for (drivebus reports both).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ScaleError {
    /// The value does not fit the raw type (or is not finite).
    Overflow,
    /// The value lies between two steps of the scale (`step` apart); writing it would round.
    BetweenSteps {
        /// The scale's step (its factor's magnitude).
        step: f64,
    },
}

impl fmt::Display for ScaleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Overflow => f.write_str("the value does not fit the raw type"),
            Self::BetweenSteps { step } => write!(
                f,
                "the value lies between two steps of {step}; it would be rounded"
            ),
        }
    }
}

impl core::error::Error for ScaleError {}

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
    #[doc(hidden)] // generated constants; users build scales from `Ratio`s
    pub const fn fixed(num: i64, den: i64, offset_num: i64, offset_den: i64) -> Scale {
        match (Ratio::new(num, den), Ratio::new(offset_num, offset_den)) {
            (Some(factor), Some(offset)) => Scale { factor, offset },
            _ => panic!("the generator emits only valid scales"),
        }
    }

    /// This scale with `offset_num / offset_den` added after the factor, for generated
    /// constants (`scale = 1 / 10, offset = -40 / 1`).
    #[doc(hidden)]
    pub const fn with_offset(self, offset_num: i64, offset_den: i64) -> Scale {
        match Ratio::new(offset_num, offset_den) {
            Some(offset) => Scale {
                factor: self.factor,
                offset,
            },
            None => panic!("the generator emits only valid offsets"),
        }
    }

    /// A scale with the given factor and no offset.
    pub const fn factor(factor: Ratio) -> Scale {
        Scale {
            factor,
            offset: Ratio::ZERO,
        }
    }

    /// Engineering value of a raw value: `raw × factor + offset`. Where every term is an exact
    /// `f64` integer it is computed as one fraction, rounded once, so that decimal steps read back
    /// as written (3 × 1/10 is 0.3, not 0.30000000000000004).
    pub fn to_engineering<R: Scalable>(self, raw: R) -> f64 {
        let raw = raw.to_f64();
        let int = |r: Ratio| (r.numerator() as f64, r.denominator() as f64);
        let ((num, den), (offset_num, offset_den)) = (int(self.factor), int(self.offset));
        // (raw·num·offset_den + offset_num·den) / (den·offset_den)
        let terms = [raw * num * offset_den, offset_num * den, den * offset_den];
        let exact = R::IS_INTEGER && terms.iter().all(|t| t.abs() < EXACT_INTEGERS);
        let numerator = terms[0] + terms[1];
        if exact && numerator.abs() < EXACT_INTEGERS {
            return numerator / terms[2];
        }
        raw * self.factor.to_f64() + self.offset.to_f64()
    }

    /// Raw value of an engineering value; refuses values that would have to be rounded or do not
    /// fit the raw type, so nothing is silently changed on its way to the drive.
    pub fn to_raw<R: Scalable>(self, value: f64) -> Result<R, ScaleError> {
        if !value.is_finite() {
            return Err(ScaleError::Overflow);
        }
        let exact = (value - self.offset.to_f64()) / self.factor.to_f64();
        if !R::IS_INTEGER {
            return R::from_f64(exact).ok_or(ScaleError::Overflow);
        }
        let nearest = round(exact);
        // A relative tolerance absorbs decimal→binary noise (49.5 / 0.01) but no real rounding.
        let tolerance = 1e-9 * nearest.abs().max(1.0);
        if (exact - nearest).abs() > tolerance {
            let step = self.factor.to_f64().abs();
            return Err(ScaleError::BetweenSteps { step });
        }
        R::from_f64(nearest).ok_or(ScaleError::Overflow)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_steps_read_back_as_written() {
        let tenths = Scale::fixed(1, 10, 0, 1);
        assert_eq!(tenths.to_engineering(3i32), 0.3);
        assert_eq!(tenths.to_engineering(-7i16), -0.7);
        let celsius = Scale::fixed(1, 10, -40, 1);
        assert_eq!(celsius.to_engineering(253u16), -14.7);
        // Beyond 2^53 the fraction is not exact: the plain product is used.
        let big = Scale::fixed(3, 7, 0, 1);
        assert_eq!(big.to_engineering(i64::MAX), i64::MAX as f64 * (3.0 / 7.0));
    }

    proptest::proptest! {
        #[test]
        fn engineering_values_round_trip_and_are_correctly_rounded(
            raw in -1_000_000i32..1_000_000,
            num in 1i64..1000,
            den in 1i64..1000,
            offset_num in -1000i64..1000,
            offset_den in 1i64..100,
        ) {
            let scale = Scale::fixed(num, den, offset_num, offset_den);
            let value = scale.to_engineering(raw);
            // The nearest f64 to the exact rational: compare against a wide integer fraction.
            let (n, d) = (
                i128::from(raw) * i128::from(num) * i128::from(offset_den)
                    + i128::from(offset_num) * i128::from(den),
                i128::from(den) * i128::from(offset_den),
            );
            proptest::prop_assert_eq!(value, n as f64 / d as f64);
            proptest::prop_assert_eq!(scale.to_raw::<i32>(value), Ok(raw));
        }
    }

    #[test]
    fn parses_rationals_and_decimals_exactly() {
        let ratio = |n, d| Ratio::new(n, d);
        assert_eq!(Ratio::parse("1/100"), ratio(1, 100));
        assert_eq!(Ratio::parse("0.1"), ratio(1, 10));
        assert_eq!(Ratio::parse("-40"), ratio(-40, 1));
        assert_eq!(Ratio::parse("1875/512"), ratio(1875, 512));
        assert_eq!(Ratio::parse("2.5/0.5"), ratio(5, 1));
        assert_eq!(Ratio::parse(" -0.25 "), ratio(-1, 4));
    }

    #[test]
    fn parse_refuses_garbage_zero_denominators_and_overflow() {
        for bad in [
            "",
            "1/0",
            "abc",
            "1/2/3",
            "0x10",
            "1e3",
            "--1",
            ".5",
            "+1",
            "99999999999999999999",
            "1.0000000000000000001",
        ] {
            assert_eq!(Ratio::parse(bad), None, "{bad}");
        }
    }

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
        assert_eq!(scale.to_raw::<i32>(1500.0), Ok(4_096_000));
    }

    #[test]
    fn volts_round_trip_through_hundredths() {
        let scale = Scale::factor(Ratio::new(1, 100).unwrap());
        assert_eq!(scale.to_engineering(4950u16), 49.5);
        assert_eq!(scale.to_raw::<u16>(49.5), Ok(4950));
    }

    #[test]
    fn values_between_steps_are_refused_not_rounded() {
        let scale = Scale::factor(Ratio::new(1, 10).unwrap());
        assert!(matches!(
            scale.to_raw::<i16>(35.55),
            Err(ScaleError::BetweenSteps { .. })
        ));
    }

    #[test]
    fn offsets_apply_after_the_factor() {
        let scale = Scale {
            factor: Ratio::new(1, 10).unwrap(),
            offset: Ratio::int(-40),
        };
        assert_eq!(scale.to_engineering(400u16), 0.0);
        assert_eq!(scale.to_raw::<u16>(-40.0), Ok(0));
    }

    #[test]
    fn raw_overflow_is_an_error() {
        assert_eq!(
            Scale::IDENTITY.to_raw::<u8>(300.0),
            Err(ScaleError::Overflow)
        );
    }
}

//! Raw-value checks generated parameters call before anything is sent. Errors carry the raw
//! values exactly ([`RawValue`](crate::interpret::RawValue)): a 64-bit raw value does not pass
//! through an `f64`.

use crate::error::ValueError;
use crate::interpret::OutsideRange;
use crate::value::Numeric;

/// Fails unless `min <= raw <= max`.
pub fn in_range<R: Numeric>(
    parameter: &'static str,
    raw: R,
    min: R,
    max: R,
) -> Result<(), ValueError> {
    if raw < min || raw > max {
        return Err(ValueError::OutOfRange {
            parameter,
            value: OutsideRange::new(raw.to_raw_value(), min.to_raw_value(), max.to_raw_value()),
        });
    }
    Ok(())
}

/// Fails unless `raw` is one of `allowed`.
pub fn one_of<R: Numeric>(
    parameter: &'static str,
    raw: R,
    allowed: &[R],
) -> Result<(), ValueError> {
    if allowed.contains(&raw) {
        return Ok(());
    }
    Err(ValueError::NotAllowed {
        parameter,
        raw: raw.to_raw_value(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interpret::RawValue;
    use crate::value::Scalable;

    #[test]
    fn range_and_set_checks() {
        assert!(in_range("a", 5u16, 1, 247).is_ok());
        assert!(matches!(
            in_range("a", 0u16, 1, 247),
            Err(ValueError::OutOfRange { .. })
        ));
        assert!(one_of("b", 192u16, &[96, 192]).is_ok());
        assert_eq!(
            one_of("b", 100u16, &[96, 192]),
            Err(ValueError::NotAllowed {
                parameter: "b",
                raw: RawValue::Int(100)
            })
        );
    }

    #[test]
    fn booleans_are_checked_as_zero_and_one() {
        assert!(in_range("c", true, true, true).is_ok());
        assert_eq!(
            in_range("c", false, true, true),
            Err(ValueError::OutOfRange {
                parameter: "c",
                value: OutsideRange::Int {
                    raw: 0,
                    min: 1,
                    max: 1
                }
            })
        );
        assert!(one_of("c", false, &[false]).is_ok());
        assert_eq!(bool::from_f64(1.0), Some(true));
        assert_eq!(bool::from_f64(0.5), None);
    }

    #[test]
    fn a_64_bit_raw_beyond_2_to_the_53_is_reported_exactly() {
        // 2^53 + 1 has no f64: through a float it would read 2^53.
        let raw = (1u64 << 53) + 1;
        assert_eq!(
            in_range("d", raw, 0, 1 << 53),
            Err(ValueError::OutOfRange {
                parameter: "d",
                value: OutsideRange::Int {
                    raw: 9_007_199_254_740_993,
                    min: 0,
                    max: 9_007_199_254_740_992
                }
            })
        );
        assert_eq!(
            one_of("d", u64::MAX, &[0]),
            Err(ValueError::NotAllowed {
                parameter: "d",
                raw: RawValue::Int(i128::from(u64::MAX))
            })
        );
    }

    #[test]
    fn floats_are_reported_as_floats() {
        assert_eq!(
            in_range("e", 1.5f32, 0.0, 1.0),
            Err(ValueError::OutOfRange {
                parameter: "e",
                value: OutsideRange::Float {
                    raw: 1.5,
                    min: 0.0,
                    max: 1.0
                }
            })
        );
    }
}

//! Raw-value checks generated parameters call before anything is sent.

use crate::error::ValueError;
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
            raw: raw.to_f64(),
            min: min.to_f64(),
            max: max.to_f64(),
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
        raw: raw.to_f64() as i128,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
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
                raw: 100
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
                raw: 0.0,
                min: 1.0,
                max: 1.0
            })
        );
        assert!(one_of("c", false, &[false]).is_ok());
        assert_eq!(bool::from_f64(1.0), Some(true));
        assert_eq!(bool::from_f64(0.5), None);
    }
}

//! Bounds set by other parameters (`bounds = { min, max, magnitude }` in a description): a
//! value must not lie beyond another parameter's current value. One comparison and one refusal
//! for the device handle's writes (`drivebus::Writable::BOUNDS`), the run-time interpreter and the
//! simulator.

use core::fmt;

/// How another parameter's current value bounds a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// The least allowed value.
    Min,
    /// The greatest allowed value.
    Max,
    /// `v` allows `-v ..= v` (Lafert: the speed setpoint within ± the full-scale velocity).
    Magnitude,
}

impl Bound {
    /// Whether `raw` lies beyond `limit`, the bounding parameter's current raw value. Compared as
    /// `i128`, so that a bound of another integer type (an unsigned full scale) compares exactly.
    #[inline]
    pub const fn breached(self, raw: i128, limit: i128) -> bool {
        match self {
            Self::Min => raw < limit,
            Self::Max => raw > limit,
            Self::Magnitude => raw.unsigned_abs() > limit.unsigned_abs() || limit < 0,
        }
    }
}

/// A write refused because its value lies beyond the current value of the parameter that
/// bounds it; nothing was written. `N` is how the two parameters are named: `&'static str` in
/// generated code, `String` in the interpreter.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutsideBound<N = &'static str> {
    /// The parameter being written.
    pub parameter: N,
    /// The parameter whose current value it broke.
    pub bound: N,
    /// The raw value asked for.
    pub raw: i128,
    /// The bound's current raw value.
    pub limit: i128,
}

impl<N: fmt::Display> fmt::Display for OutsideBound<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self {
            parameter,
            bound,
            raw,
            limit,
        } = self;
        write!(
            f,
            "{parameter}: raw value {raw} is beyond the current value {limit} of {bound}"
        )
    }
}

impl<N: fmt::Display + fmt::Debug> core::error::Error for OutsideBound<N> {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_bound_refuses_only_beyond_its_side() {
        assert!(Bound::Min.breached(-1, 0) && !Bound::Min.breached(0, 0));
        assert!(Bound::Max.breached(11, 10) && !Bound::Max.breached(10, 10));
        assert!(!Bound::Magnitude.breached(-3000, 3000) && !Bound::Magnitude.breached(3000, 3000));
        assert!(Bound::Magnitude.breached(-3001, 3000) && Bound::Magnitude.breached(3001, 3000));
    }
}

//! The inclusive raw range of a described value, and the one range check of described values.

use crate::Number;

/// An inclusive raw range.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Range {
    /// Smallest raw value.
    pub min: Number,
    /// Largest raw value.
    pub max: Number,
}

impl Range {
    /// Where a value lies, given how it compares with a bound: `Less` below the minimum,
    /// `Greater` above the maximum, `Equal` within; `None` if it does not compare (NaN). The one
    /// range check of described values, for the validator, the simulator and the CLI alike.
    pub fn locate(
        &self,
        compare: impl Fn(Number) -> Option<core::cmp::Ordering>,
    ) -> Option<core::cmp::Ordering> {
        use core::cmp::Ordering::{Equal, Greater, Less};
        match (compare(self.min)?, compare(self.max)?) {
            (Less, _) => Some(Less),
            (_, Greater) => Some(Greater),
            _ => Some(Equal),
        }
    }

    /// Whether `n` lies within the range, compared exactly ([`Number::compare`]).
    pub fn contains(&self, n: Number) -> bool {
        self.locate(|bound| n.compare(bound)) == Some(core::cmp::Ordering::Equal)
    }
}

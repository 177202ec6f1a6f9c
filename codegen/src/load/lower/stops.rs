//! Lowering of `stops = true` / `stops = [{ mask, value }, ...]`: the writes of a parameter that
//! stop the drive. Whether they fit the parameter is the rule `stops_are_always_sendable`.

use toml::Spanned;

use super::{Lowering, VALUE_RULE};
use crate::ir;
use crate::load::raw::RawStops;

impl Lowering<'_> {
    /// The stop writes (`Some(None)`: `stops = false`); `None` when a pattern is negative.
    pub(super) fn stop_writes(
        &mut self,
        raw: &Spanned<RawStops>,
    ) -> Option<Option<ir::StopWrites>> {
        let span = self.span(raw);
        let patterns = match raw.get_ref() {
            RawStops::Every(false) => return Some(None),
            RawStops::Every(true) => None,
            RawStops::Matching(patterns) => {
                let mut lowered = Vec::with_capacity(patterns.len());
                for p in patterns {
                    let (Ok(mask), Ok(value)) = (u64::try_from(p.mask), u64::try_from(p.value))
                    else {
                        self.error(
                            VALUE_RULE,
                            span,
                            "a stop pattern's `mask` and `value` are bit patterns, not negative",
                        );
                        return None;
                    };
                    lowered.push(drivebus_model::StopPattern { mask, value });
                }
                Some(lowered)
            }
        };
        Some(Some(ir::StopWrites { patterns, span }))
    }
}

//! Writes that stop the drive: `stops = true` (every write of a stop command, Lenze smd `stop`)
//! or `stops = [{ mask, value }, ...]` (the values of a word that stop, disable or quick-stop the
//! drive: a CiA 402 controlword without "enable operation"). They are never refused client-side
//! ([`drivebus::stop`]).

use drivebus_model::{StopPattern, Stops};
use serde::Serialize;

use crate::diagnostic::Span;

/// Which writes of a parameter stop the drive.
#[derive(Debug, Clone, Serialize)]
pub struct StopWrites {
    /// Every write (`None`), or the values matching one of these patterns.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub patterns: Option<Vec<StopPattern>>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

impl StopWrites {
    /// The runtime's view of these writes.
    pub fn view(&self) -> Stops<'_> {
        match &self.patterns {
            None => Stops::Always,
            Some(patterns) => Stops::Matching(patterns),
        }
    }
}

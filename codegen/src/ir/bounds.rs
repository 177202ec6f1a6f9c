//! Bounds set by other parameters: `bounds = { min = "c10", max = "c11" }` says the parameter
//! lies within the current values of those parameters (Lenze smd #40 within C10...C11);
//! `bounds = { magnitude = "full_scale_velocity" }` says it lies within ± the current value of
//! one (the Lafert speed setpoint). The static `range` stays the envelope; the bounds are checked
//! against the drive at run time.

use serde::Serialize;

use crate::diagnostic::Span;

/// The parameters whose current values bound a parameter.
#[derive(Debug, Clone, Serialize)]
pub struct Bounds {
    /// The parameter whose value is the least allowed value.
    pub min: Option<String>,
    /// The parameter whose value is the greatest allowed value.
    pub max: Option<String>,
    /// The parameter whose value `v` bounds this one to `-v..=v`. Left out of the JSON when
    /// absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub magnitude: Option<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

impl Bounds {
    /// The bounding parameters, lower first, the magnitude last.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.min
            .iter()
            .chain(&self.max)
            .chain(&self.magnitude)
            .map(String::as_str)
    }
}

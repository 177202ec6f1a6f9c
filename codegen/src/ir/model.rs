//! Per-model constants: values fixed by the product model the user names when opening a drive
//! handle (Kinco: the drive's peak current; ez-Wheel SWD: the gear ratio), read by run-time scale
//! expressions like parameters.

use serde::Serialize;

use drivebus_model::Ratio;

use super::Citation;
use crate::diagnostic::Span;

/// A constant whose value each model gives.
#[derive(Debug, Clone, Serialize)]
pub struct Constant {
    /// snake_case name, as scale expressions read it.
    pub name: String,
    /// Documentation.
    pub doc: Option<String>,
    /// Unit symbol of the value (documentation only: expressions read the number).
    pub unit: Option<String>,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// A product model and the values of the constants.
#[derive(Debug, Clone, Serialize)]
pub struct Model {
    /// snake_case name; the generated `Model` enum's variant is its CamelCase form.
    pub name: String,
    /// Documentation.
    pub doc: Option<String>,
    /// `(constant, exact value)`, sorted by constant name.
    pub constants: Vec<(String, Ratio)>,
    /// Citation.
    pub source: Option<Citation>,
    /// Errata decision.
    pub erratum: Option<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
    /// Where its constants are written.
    #[serde(skip)]
    pub constants_span: Span,
}

impl Model {
    /// The value of `constant` in this model.
    pub fn value(&self, constant: &str) -> Option<Ratio> {
        self.constants
            .iter()
            .find(|(name, _)| name == constant)
            .map(|(_, v)| *v)
    }
}

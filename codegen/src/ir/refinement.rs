//! A `[[refine]]` entry: a description adds protocol addresses to a parameter of an included
//! profile and overrides what its drive does differently, citing its own manual.

use serde::Serialize;

use super::Citation;
use crate::diagnostic::Span;

/// What one `[[refine]]` entry changed on an included parameter.
#[derive(Debug, Clone, Serialize)]
pub struct Refinement {
    /// The refined parameter.
    pub parameter: String,
    /// The keys it added or overrode (`modbus`, `rs232`, `canopen`, `unit`, `scale`, `default`,
    /// `range`, `allowed`, `enum`, `doc`).
    pub keys: Vec<String>,
    /// The citation of the refinement.
    pub source: Option<Citation>,
    /// Errata decision.
    pub erratum: Option<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

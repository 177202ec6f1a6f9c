//! A member repeated over a run of sub-indices (`subindex = "1..=8"`), described once. The loader
//! expands it into one parameter per sub-index (named `<name>_<sub-index>`), so every emitter,
//! the simulator and the EDS export see ordinary objects; this record keeps the run together so
//! the generated handle offers one indexed, range-checked accessor (`drive.<name>(n)`).

use serde::Serialize;

use crate::diagnostic::Span;

/// A run of sub-indices of one object described by a single member.
#[derive(Debug, Clone, Serialize)]
pub struct IndexedParameter {
    /// Name of the run: the indexed accessor's name.
    pub name: String,
    /// Documentation of the member.
    pub doc: Option<String>,
    /// Object index.
    pub index: u16,
    /// First sub-index of the run.
    pub first: u8,
    /// Last sub-index of the run (inclusive).
    pub last: u8,
    /// The expanded parameters, one per sub-index from `first` to `last`.
    pub members: Vec<String>,
    /// Span of the member's name.
    #[serde(skip)]
    pub span: Span,
}

impl IndexedParameter {
    /// The name of the parameter the run expands to at `subindex`.
    pub fn member_name(name: &str, subindex: u8) -> String {
        format!("{name}_{subindex}")
    }
}

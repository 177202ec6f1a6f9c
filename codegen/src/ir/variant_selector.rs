//! Variants chosen by the drive at run time: `[[variant]] selected_by = { parameter, value }`
//! says the drive is in that variant when `parameter` reads `value` (Lenze smd: register #50
//! reads 400 for PC400, 507 for PC507).

use serde::Serialize;

use super::{Device, Parameter};
use crate::diagnostic::Span;

/// The reading of a parameter that identifies a variant.
#[derive(Debug, Clone, Serialize)]
pub struct VariantSelector {
    /// The parameter the drive reports its variant in.
    pub parameter: String,
    /// The raw value it reads in this variant.
    pub value: i64,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

impl Device {
    /// The parameter that selects the variant, if every variant names it (checked by
    /// `variant_selectors_resolve`), with each variant's index and value.
    pub fn variant_selection(&self) -> Option<(&Parameter, Vec<(usize, i64)>)> {
        let first = self.variants.first()?.selected_by.as_ref()?;
        let parameter = self.parameter(&first.parameter)?;
        let values = self
            .variants
            .iter()
            .enumerate()
            .map(|(i, v)| {
                v.selected_by
                    .as_ref()
                    .filter(|s| s.parameter == first.parameter)
                    .map(|s| (i, s.value))
            })
            .collect::<Option<Vec<_>>>()?;
        Some((parameter, values))
    }
}

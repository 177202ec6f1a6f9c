//! The variant a simulated drive serves when its description says how the drive reports it
//! (`[[variant]] selected_by`): the one whose value the selecting parameter holds, so
//! `drivegen sim descriptions/lenze-smd --set parameter_configuration=507` serves PC507.

use crate::store::Store;

/// The variant selected by the stored value of the selecting parameter; `None` when the
/// description selects no variant this way or the value selects none (the caller serves its
/// default then).
pub fn selected_variant(store: &Store) -> Option<String> {
    let device = store.device();
    let (parameter, values) = device.variant_selection()?;
    let raw = store.int(store.id(&parameter.name)?)?;
    values
        .into_iter()
        .find(|(_, value)| i128::from(*value) == raw)
        .map(|(i, _)| device.variants[i].name.clone())
}

/// Whether `parameter` exists in `variant` (its `variants` list; every parameter exists when no
/// variant is served).
pub fn exists_in(parameter: &drivegen::ir::Parameter, variant: Option<&str>) -> bool {
    match variant {
        Some(v) => parameter.variants.is_empty() || parameter.variants.iter().any(|p| p == v),
        None => true,
    }
}

//! The check every described value passes before it is sent or stored: within its type, its
//! range and its allowed values. The simulator refuses client writes with it, the CLI refuses
//! typed input with it.

use core::cmp::Ordering;

use super::{Described, RawValue};

/// Why a raw value is not a valid value of its parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Breach {
    /// Beyond the bounds of the parameter's integer type.
    OutsideType,
    /// Below the described range.
    BelowRange,
    /// Above the described range.
    AboveRange,
    /// Not a number (NaN), so within no range.
    Unordered,
    /// Not one of the allowed values.
    NotAllowed,
}

/// Checks `raw` against the type, the range and the allowed values of `parameter`.
pub fn check(parameter: &impl Described, raw: RawValue) -> Result<(), Breach> {
    if let (Some((min, max)), RawValue::Int(int)) = (parameter.data_type().integer_bounds(), raw) {
        if int < min || int > max {
            return Err(Breach::OutsideType);
        }
    }
    let against = |bound: super::Number| bound.compare_raw(raw);
    match parameter.range().and_then(|range| range.locate(against)) {
        Some(Ordering::Less) => return Err(Breach::BelowRange),
        Some(Ordering::Greater) => return Err(Breach::AboveRange),
        Some(Ordering::Equal) => {}
        None if parameter.range().is_some() => return Err(Breach::Unordered),
        None => {}
    }
    let allowed = parameter.allowed();
    if !allowed.is_empty() && !allowed.iter().any(|a| against(*a) == Some(Ordering::Equal)) {
        return Err(Breach::NotAllowed);
    }
    Ok(())
}

//! Bounds set by other parameters (`bounds = { min, max, magnitude }`): a write beyond the
//! current value of a bounding parameter is refused, as the drive refuses it (Lenze smd #40
//! within C10...C11, the Lafert speed setpoint within ± the full-scale velocity).
//!
//! A bounding parameter that still reads 0 while the description gives it no default has not been
//! set (a Lafert full scale depends on the motor fitted; `--set` gives it): it bounds nothing.

use super::Behaviour;
use crate::refusal::Refusal;
use crate::store::{ParamId, Store};

/// The bounding parameters of one bounded parameter.
#[derive(Debug, Clone, Copy)]
struct BoundIds {
    min: Option<ParamId>,
    max: Option<ParamId>,
    magnitude: Option<ParamId>,
}

/// Every bounded parameter of the description, with its bounds.
#[derive(Debug)]
pub struct Bounds {
    bounded: Vec<(ParamId, BoundIds)>,
}

impl Bounds {
    /// Present when the description bounds a parameter by others.
    pub fn detect(store: &Store) -> Option<Self> {
        let bounded: Vec<(ParamId, BoundIds)> = store
            .device()
            .parameters
            .iter()
            .enumerate()
            .filter_map(|(id, p)| {
                let b = p.bounds.as_ref()?;
                let find = |name: &Option<String>| name.as_deref().and_then(|n| store.id(n));
                let ids = BoundIds {
                    min: find(&b.min),
                    max: find(&b.max),
                    magnitude: find(&b.magnitude),
                };
                Some((id, ids))
            })
            .collect();
        (!bounded.is_empty()).then_some(Self { bounded })
    }
}

/// The current value of `bound`, unless it has not been set (see the module docs).
fn current(store: &Store, bound: ParamId) -> Option<i128> {
    let value = store.int(bound)?;
    let unset = value == 0 && store.parameter(bound).default.is_none();
    (!unset).then_some(value)
}

impl Behaviour for Bounds {
    fn accept(&self, store: &Store, id: ParamId, bytes: &[u8]) -> Result<(), Refusal> {
        let Some((_, ids)) = self.bounded.iter().find(|(bounded, _)| *bounded == id) else {
            return Ok(());
        };
        let Some(value) = crate::raw::to_int(store.parameter(id).data_type, bytes) else {
            return Ok(());
        };
        let limit = |bound: Option<ParamId>| bound.and_then(|b| current(store, b));
        if limit(ids.min).is_some_and(|min| value < min) {
            return Err(Refusal::TooLow);
        }
        if limit(ids.max).is_some_and(|max| value > max) {
            return Err(Refusal::TooHigh);
        }
        match limit(ids.magnitude) {
            Some(full) if value > full => Err(Refusal::TooHigh),
            Some(full) if value < -full => Err(Refusal::TooLow),
            _ => Ok(()),
        }
    }
}

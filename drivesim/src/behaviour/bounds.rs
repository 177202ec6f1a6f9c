//! Bounds set by other parameters (`bounds = { min, max, magnitude }`): a write beyond the
//! current value of a bounding parameter is refused, as the drive refuses it (Lenze smd #40
//! within C10...C11, the Lafert speed setpoint within ± the full-scale velocity).
//!
//! A bounding parameter that still reads 0 while the description gives it no default has not been
//! set (a Lafert full scale depends on the motor fitted; `--set` gives it): it bounds nothing.

use drivebus::interpret::Described;
use drivebus::Bound;

use super::Behaviour;
use crate::refusal::Refusal;
use crate::store::{ParamId, Store};

/// Every bounded parameter of the description, with its bounding parameters and how each bounds.
#[derive(Debug)]
pub struct Bounds {
    bounded: Vec<(ParamId, Vec<(Bound, ParamId)>)>,
}

impl Bounds {
    /// Present when the description bounds a parameter by others.
    pub fn detect(store: &Store) -> Option<Self> {
        let bounded: Vec<(ParamId, Vec<(Bound, ParamId)>)> = store
            .device()
            .parameters
            .iter()
            .enumerate()
            .filter(|(_, p)| p.bounds.is_some())
            .map(|(id, p)| {
                let ids = p
                    .bounded_by()
                    .each()
                    .filter_map(|(kind, name)| Some((kind, store.id(name)?)))
                    .collect();
                (id, ids)
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
        let Some((_, bounds)) = self.bounded.iter().find(|(bounded, _)| *bounded == id) else {
            return Ok(());
        };
        let Some(value) = crate::raw::to_int(store.parameter(id).data_type, bytes) else {
            return Ok(());
        };
        for &(kind, bound) in bounds {
            let breached = current(store, bound).is_some_and(|limit| kind.breached(value, limit));
            match (breached, kind) {
                (false, _) => {}
                (true, Bound::Min) => return Err(Refusal::TooLow),
                (true, Bound::Magnitude) if value < 0 => return Err(Refusal::TooLow),
                (true, _) => return Err(Refusal::TooHigh),
            }
        }
        Ok(())
    }
}

//! The CiA 402 velocity mode (vl) ramp: acceleration 6048h and deceleration 6049h, each a delta
//! speed (sub 1) over a delta time in seconds (sub 2), e.g. the SWD's 500 rpm per 1 s (manual
//! lines 2643-2651). The motor uses it when the description has no profile rates (6083h/6084h).

use super::object;
use crate::store::{ParamId, Store};

/// One vl ramp: delta speed over delta time.
#[derive(Debug, Clone, Copy)]
struct Ramp {
    delta_speed: ParamId,
    delta_time: ParamId,
}

impl Ramp {
    fn detect(store: &mut Store, index: u16) -> Option<Self> {
        Some(Self {
            delta_speed: object(store, index, 1)?,
            delta_time: object(store, index, 2)?,
        })
    }

    /// Speed units per second; `None` when the time is zero (no ramp).
    fn rate(self, store: &Store) -> Option<f64> {
        let value = |id| store.int(id).unwrap_or(0) as f64;
        let time = value(self.delta_time);
        (time > 0.0).then(|| value(self.delta_speed) / time)
    }
}

/// The vl acceleration and deceleration ramps.
#[derive(Debug, Clone, Copy)]
pub struct VlRamp {
    acceleration: Ramp,
    deceleration: Ramp,
}

impl VlRamp {
    /// Present when the description has both 6048h and 6049h with sub-indices 1 and 2.
    pub fn detect(store: &mut Store) -> Option<Self> {
        Some(Self {
            acceleration: Ramp::detect(store, 0x6048)?,
            deceleration: Ramp::detect(store, 0x6049)?,
        })
    }

    /// The rate towards a setpoint further from zero (`speeding_up`) or nearer to it.
    pub fn rate(&self, store: &Store, speeding_up: bool) -> Option<f64> {
        let ramp = if speeding_up {
            self.acceleration
        } else {
            self.deceleration
        };
        ramp.rate(store).filter(|r| *r > 0.0)
    }
}

//! A simple motor: the actual speed follows the setpoint the state machine enables, along the
//! ramp the description gives that setpoint (`[[ramp]]`, see [`SetpointRamp`]), and stops at once
//! on a quick stop or when the power stage is off. Without a ramp, the speed jumps. The speed
//! shows in the vendor machine's `actual` parameter and the CiA 402 actual values.
//!
//! Speeds are raw values: `state_machines_resolve` holds a machine's `actual` to its setpoint's
//! unit and scale; the CiA 402 actual values are in their setpoints' units (606Ch in those of
//! 60FFh, 6044h in those of 6042h). A setpoint's bounds are checked by `Bounds`.

use std::time::Duration;

use super::ramp::SetpointRamp;
use super::{object, Behaviour, Motion, Shared};
use crate::store::{ParamId, Store};

/// The motor model.
#[derive(Debug)]
pub struct Motor {
    actuals: Vec<ParamId>,
    ramps: Vec<SetpointRamp>,
    speed: f64,
}

impl Motor {
    /// Present when the description has an actual-speed value to show: the vendor state
    /// machine's `actual`, the CiA 402 velocity actual value (606Ch) or the vl one (6044h).
    pub fn detect(store: &mut Store) -> Option<Self> {
        let vendor = store.device().state_machine.as_ref();
        let actuals: Vec<ParamId> = vendor
            .and_then(|m| m.actual.as_deref())
            .and_then(|name| store.id(name))
            .into_iter()
            .chain(object(store, 0x606C, 0))
            // The vl velocity actual value (e.g. the ez-Wheel SWD's), in the units of 6042h.
            .chain(object(store, 0x6044, 0))
            .collect();
        if actuals.is_empty() {
            return None;
        }
        Some(Self {
            actuals,
            ramps: SetpointRamp::detect(store),
            speed: 0.0,
        })
    }

    /// Speed change per second towards `target` set in `setpoint`; `None` = at once.
    fn rate(&self, store: &Store, setpoint: ParamId, target: f64) -> Option<f64> {
        let speeding_up = target.abs() > self.speed.abs();
        self.ramps
            .iter()
            .find(|r| r.shapes(setpoint))?
            .rate(store, speeding_up)
    }
}

impl Behaviour for Motor {
    fn tick(&mut self, store: &mut Store, shared: &mut Shared, dt: Duration) {
        let (setpoint, target) = match shared.motion {
            Motion::Following(setpoint) => (setpoint, store.int(setpoint).unwrap_or(0) as f64),
            Motion::Disabled | Motion::QuickStop => {
                self.speed = 0.0;
                (0, 0.0)
            }
        };
        let mut seconds = dt.as_secs_f64();
        let mut spent = false;
        // A reversal returns to zero on the deceleration ramp, then reaches the new setpoint on
        // the acceleration ramp (SWD manual line 2620; CiA 402 ramps alike).
        if self.speed != 0.0 && target != 0.0 && target.signum() != self.speed.signum() {
            match self.rate(store, setpoint, 0.0) {
                Some(rate) if self.speed.abs() > rate * seconds => {
                    self.speed -= self.speed.signum() * rate * seconds;
                    spent = true;
                }
                Some(rate) => {
                    seconds -= self.speed.abs() / rate;
                    self.speed = 0.0;
                }
                None => self.speed = 0.0,
            }
        }
        let rate = if target == self.speed {
            None
        } else {
            self.rate(store, setpoint, target)
        };
        self.speed = match rate {
            _ if spent => self.speed,
            Some(rate) => {
                let step = rate * seconds;
                self.speed + (target - self.speed).clamp(-step, step)
            }
            None => target,
        };
        for &id in &self.actuals {
            store.set_int(id, self.speed.round() as i128);
        }
    }

    fn reset(&mut self, store: &mut Store, shared: &mut Shared) {
        self.tick(store, shared, Duration::ZERO);
    }
}

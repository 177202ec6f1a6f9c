//! A simple motor: the actual speed follows the setpoint the state machine enables, along the
//! ramp the description gives that setpoint (`[[ramp]]`, see [`SetpointRamp`]), ramps to zero
//! along its deceleration in a `ramp-stop` state, and stops at once on a quick stop or when the
//! power stage is off. Without a ramp, the speed jumps; a ramp's polarity bit, while set, makes
//! the motor follow the setpoint reversed. The speed shows in the vendor machine's `actual`
//! parameter and the CiA 402 actual values; whether it is rising, falling, steady or at zero goes
//! to the state machine's status patterns ([`Shared::phase`]).
//!
//! Speeds are raw values: `state_machines_resolve` holds a machine's `actual` to its setpoint's
//! unit and scale; the CiA 402 actual values are in their setpoints' units (606Ch in those of
//! 60FFh, 6044h in those of 6042h). A setpoint's bounds are checked by `Bounds`.

use std::time::Duration;

use drivegen::ir::SpeedPhase;

use super::ramp::SetpointRamp;
use super::{object, Behaviour, Motion, Shared};
use crate::store::{ParamId, Store};

/// The motor model.
#[derive(Debug)]
pub struct Motor {
    actuals: Vec<ParamId>,
    /// The vendor machine's `commanded` parameter: shows the speed the motor heads for.
    commanded: Option<ParamId>,
    ramps: Vec<SetpointRamp>,
    speed: f64,
}

impl Motor {
    /// The setpoint the motor follows and the speed it heads for (the setpoint's value, reversed
    /// while its ramp's polarity bit is set; 0 in a ramp-stop); `None` while it is stopped.
    fn heading(&self, store: &Store, motion: Motion) -> Option<(ParamId, f64)> {
        match motion {
            Motion::Following(setpoint) => {
                let sign = self
                    .ramps
                    .iter()
                    .find(|r| r.shapes(setpoint))
                    .map_or(1.0, |r| r.sign(store));
                Some((setpoint, sign * store.int(setpoint).unwrap_or(0) as f64))
            }
            Motion::RampStop(setpoint) | Motion::RampStopAt(setpoint, _) => Some((setpoint, 0.0)),
            Motion::Disabled | Motion::QuickStop => None,
        }
    }

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
        let commanded = vendor
            .and_then(|m| m.commanded.as_deref())
            .and_then(|name| store.id(name));
        Some(Self {
            actuals,
            commanded,
            ramps: SetpointRamp::detect(store),
            speed: 0.0,
        })
    }

    /// A reversal first returns to zero on the deceleration ramp, then reaches the new setpoint
    /// on the acceleration ramp (SWD manual line 2620; CiA 402 ramps alike): takes what of
    /// `seconds` the way to zero needs, and says whether that was all of them.
    fn through_zero(
        &mut self,
        store: &Store,
        setpoint: ParamId,
        target: f64,
        seconds: &mut f64,
    ) -> bool {
        if self.speed == 0.0 || target == 0.0 || target.signum() == self.speed.signum() {
            return false;
        }
        match self.rate(store, setpoint, 0.0) {
            Some(rate) if self.speed.abs() > rate * *seconds => {
                self.speed -= self.speed.signum() * rate * *seconds;
                true
            }
            Some(rate) => {
                *seconds -= self.speed.abs() / rate;
                self.speed = 0.0;
                false
            }
            None => {
                self.speed = 0.0;
                false
            }
        }
    }

    /// Speed change per second in `motion`: its own deceleration in a [`Motion::RampStopAt`],
    /// else the setpoint's ramp towards `target`; `None` = at once.
    fn motion_rate(
        &self,
        store: &Store,
        motion: Motion,
        setpoint: ParamId,
        target: f64,
    ) -> Option<f64> {
        match motion {
            Motion::RampStopAt(setpoint, deceleration) => self
                .ramps
                .iter()
                .find(|r| r.shapes(setpoint))?
                .rate_of(store, deceleration),
            _ => self.rate(store, setpoint, target),
        }
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

/// Where `speed` is relative to `target`, as the raw values shown compare (a speed that shows
/// as the target is at the target).
fn phase(speed: f64, target: f64) -> SpeedPhase {
    let (speed, target) = (speed.round(), target.round());
    if target.abs() > speed.abs() {
        SpeedPhase::Rising
    } else if target.abs() < speed.abs() {
        SpeedPhase::Falling
    } else if target == 0.0 {
        SpeedPhase::Zero
    } else {
        SpeedPhase::Steady
    }
}

impl Behaviour for Motor {
    /// A new motion or setpoint changes where the speed heads at once, before it moves.
    fn written(&mut self, store: &mut Store, shared: &mut Shared, _id: ParamId) {
        let target = self.heading(store, shared.motion).map(|(_, target)| target);
        shared.phase = target.map(|target| phase(self.speed, target));
        if let Some(id) = self.commanded {
            store.set_int(id, target.unwrap_or(0.0).round() as i128);
        }
    }

    fn tick(&mut self, store: &mut Store, shared: &mut Shared, dt: Duration) {
        let (setpoint, target) = self.heading(store, shared.motion).unwrap_or_else(|| {
            self.speed = 0.0;
            (0, 0.0)
        });
        let mut seconds = dt.as_secs_f64();
        let spent = self.through_zero(store, setpoint, target, &mut seconds);
        let rate = if target == self.speed {
            None
        } else {
            self.motion_rate(store, shared.motion, setpoint, target)
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
        if let Some(id) = self.commanded {
            store.set_int(id, target.round() as i128);
        }
        shared.phase = self
            .heading(store, shared.motion)
            .map(|(_, target)| phase(self.speed, target));
    }

    fn reset(&mut self, store: &mut Store, shared: &mut Shared) {
        self.tick(store, shared, Duration::ZERO);
    }
}

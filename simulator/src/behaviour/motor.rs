//! A simple motor: the actual speed follows the setpoint the state machine enables, along the
//! described ramp, and stops at once on a quick stop or when the power stage is off.
//!
//! Speeds are raw values: the setpoint and the actual speed registers of one drive use the same
//! scale in every shipped description. The ramp comes from whichever the description has:
//! Lafert-style ramp times (`speed_ramp_up` / `speed_ramp_down`, ms from 0 to
//! the setpoint's magnitude bound, switched by `ramp_enable`), or CiA 402 profile acceleration /
//! deceleration (6083h / 6084h, speed units per second). Without either, the speed jumps.
//! The bound itself is checked by [`Bounds`].

use std::time::Duration;

use super::bounds::Bounds;
use super::vl_ramp::VlRamp;
use super::{object, Behaviour, Motion, Shared};
use crate::store::{ParamId, Store};

/// Span a ramp time refers to when the setpoint has no (set) magnitude bound.
const DEFAULT_FULL_SCALE: f64 = 3000.0;

/// Lafert-style ramp: milliseconds from 0 to full scale.
#[derive(Debug, Clone, Copy)]
struct RampTimes {
    up: ParamId,
    down: ParamId,
    enable: Option<ParamId>,
    /// The state machine's setpoint's magnitude bound: the span the ramp times refer to.
    span: Option<ParamId>,
}

/// CiA 402 profile ramp: speed units per second.
#[derive(Debug, Clone, Copy)]
struct RampRates {
    up: ParamId,
    down: ParamId,
}

/// The motor model.
#[derive(Debug)]
pub struct Motor {
    actuals: Vec<ParamId>,
    times: Option<RampTimes>,
    rates: Option<RampRates>,
    vl: Option<VlRamp>,
    speed: f64,
}

impl Motor {
    /// Present when the description has an actual-speed value to show.
    pub fn detect(store: &mut Store) -> Option<Self> {
        let actuals: Vec<ParamId> = ["velocity_average"]
            .iter()
            .filter_map(|name| store.id(name))
            .chain(object(store, 0x606C, 0))
            // The vl velocity actual value (e.g. the ez-Wheel SWD's), in the units of 6042h.
            .chain(object(store, 0x6044, 0))
            .collect();
        if actuals.is_empty() {
            return None;
        }
        let times = store
            .id("speed_ramp_up")
            .zip(store.id("speed_ramp_down"))
            .map(|(up, down)| RampTimes {
                up,
                down,
                enable: store.id("ramp_enable"),
                span: setpoint_span(store),
            });
        let rates = object(store, 0x6083, 0)
            .zip(object(store, 0x6084, 0))
            .map(|(up, down)| RampRates { up, down });
        Some(Self {
            actuals,
            times,
            rates,
            vl: VlRamp::detect(store),
            speed: 0.0,
        })
    }

    /// Speed change per second towards `target` set in `setpoint`; `None` = at once. A CANopen
    /// setpoint ramps with the profile rates, a Modbus one with the ramp times.
    fn rate(&self, store: &Store, setpoint: ParamId, target: f64) -> Option<f64> {
        let speeding_up = target.abs() > self.speed.abs();
        let value = |id| store.int(id).unwrap_or(0) as f64;
        if store.parameter(setpoint).modbus.is_empty() {
            let Some(rates) = self.rates else {
                return self.vl?.rate(store, speeding_up);
            };
            return Some(value(if speeding_up { rates.up } else { rates.down }))
                .filter(|r| *r > 0.0);
        }
        let times = self.times?;
        if times.enable.is_some_and(|id| value(id) == 0.0) {
            return None;
        }
        let ms = value(if speeding_up { times.up } else { times.down });
        let span = times
            .span
            .map(value)
            .filter(|v| *v > 0.0)
            .unwrap_or(DEFAULT_FULL_SCALE);
        (ms > 0.0).then(|| span * 1000.0 / ms)
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
        let rate = if target == self.speed {
            None
        } else {
            self.rate(store, setpoint, target)
        };
        self.speed = match rate {
            Some(rate) => {
                let step = rate * dt.as_secs_f64();
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

/// The magnitude bound of the setpoint the description's state machine follows, looked up once.
fn setpoint_span(store: &Store) -> Option<ParamId> {
    let machine = store.device().state_machine.as_ref()?;
    let setpoint = store.id(machine.setpoint.as_deref()?)?;
    Bounds::magnitude_of(store, setpoint)
}

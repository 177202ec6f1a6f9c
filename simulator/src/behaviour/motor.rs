//! A simple motor: the actual speed follows the setpoint the state machine enables, along the
//! described ramp, and stops at once on a quick stop or when the power stage is off.
//!
//! Speeds are raw values: the setpoint and the actual speed registers of one drive use the same
//! scale in every shipped description. The ramp comes from whichever the description has:
//! Lafert-style ramp times (`speed_ramp_up` / `speed_ramp_down`, ms from 0 to
//! `full_scale_velocity`, switched by `ramp_enable`), or CiA 402 profile acceleration /
//! deceleration (6083h / 6084h, speed units per second). Without either, the speed jumps.

use std::time::Duration;

use super::{object, Behaviour, Motion, Shared};
use crate::store::{ParamId, Store};

/// Span a ramp time refers to when the description has no full-scale velocity value.
const DEFAULT_FULL_SCALE: f64 = 3000.0;

/// How the ramp is described.
#[derive(Debug, Clone, Copy)]
enum Ramp {
    /// Milliseconds from 0 to full scale.
    Times {
        up: ParamId,
        down: ParamId,
        full_scale: Option<ParamId>,
        enable: Option<ParamId>,
    },
    /// Speed units per second.
    Rates { up: ParamId, down: ParamId },
    /// No ramp.
    None,
}

/// The motor model.
#[derive(Debug)]
pub struct Motor {
    actuals: Vec<ParamId>,
    ramp: Ramp,
    speed: f64,
}

impl Motor {
    /// Present when the description has an actual-speed value to show.
    pub fn detect(store: &mut Store) -> Option<Self> {
        let actuals: Vec<ParamId> = ["velocity_average"]
            .iter()
            .filter_map(|name| store.id(name))
            .chain(object(store, 0x606C, 0))
            .collect();
        if actuals.is_empty() {
            return None;
        }
        let ramp = match (store.id("speed_ramp_up"), store.id("speed_ramp_down")) {
            (Some(up), Some(down)) => Ramp::Times {
                up,
                down,
                full_scale: store.id("full_scale_velocity"),
                enable: store.id("ramp_enable"),
            },
            _ => match (object(store, 0x6083, 0), object(store, 0x6084, 0)) {
                (Some(up), Some(down)) => Ramp::Rates { up, down },
                _ => Ramp::None,
            },
        };
        Some(Self {
            actuals,
            ramp,
            speed: 0.0,
        })
    }

    /// Speed change per second towards `target`; `None` = at once.
    fn rate(&self, store: &Store, target: f64) -> Option<f64> {
        let speeding_up = target.abs() > self.speed.abs();
        let value = |id| store.int(id).unwrap_or(0) as f64;
        match self.ramp {
            Ramp::Times {
                up,
                down,
                full_scale,
                enable,
            } => {
                if enable.is_some_and(|id| value(id) == 0.0) {
                    return None;
                }
                let ms = value(if speeding_up { up } else { down });
                let span = full_scale
                    .map(value)
                    .filter(|v| *v > 0.0)
                    .unwrap_or(DEFAULT_FULL_SCALE);
                (ms > 0.0).then(|| span * 1000.0 / ms)
            }
            Ramp::Rates { up, down } => {
                Some(value(if speeding_up { up } else { down })).filter(|r| *r > 0.0)
            }
            Ramp::None => None,
        }
    }
}

impl Behaviour for Motor {
    fn tick(&mut self, store: &mut Store, shared: &mut Shared, dt: Duration) {
        let target = match shared.motion {
            Motion::Following(setpoint) => store.int(setpoint).unwrap_or(0) as f64,
            Motion::Disabled | Motion::QuickStop => {
                self.speed = 0.0;
                0.0
            }
        };
        self.speed = match self.rate(store, target) {
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

//! Profile torque (CiA 402 mode 4) and cyclic synchronous torque (mode 10) against a simple
//! load, chosen when the description has the target torque (6071h) and the velocity actual value
//! (606Ch): in operation enabled the torque demand moves to 6071h at the torque slope 6087h (per
//! second; without one, and in cst where each set point taken at a SYNC is the demand, at once),
//! and the
//! load's speed follows `dv/dt = GAIN · torque − FRICTION · v` (an inertia with viscous
//! friction, so a constant torque settles at a speed of `GAIN / FRICTION` per torque unit). The
//! speed shows in 606Ch (the axis integrates it into the position), the torque in 6077h if the
//! drive has it; target reached (statusword bit 10) is the demand standing on the target. No
//! drive-specific code: the units are the description's raw ones.

use std::time::Duration;

use drivebus::control::mode_bits::{CYCLIC_SYNC_TORQUE, PROFILE_TORQUE};

use super::{object, Behaviour, Shared};
use crate::store::{ParamId, Store};

/// Speed gained per second per torque unit, in velocity units.
pub const GAIN: f64 = 1_000.0;
/// Viscous friction: the share of the speed lost per second.
pub const FRICTION: f64 = 2.0;
/// Integration step, as the positioning axis's.
const STEP: f64 = 0.001;

/// The load under torque.
#[derive(Debug)]
pub struct TorqueLoad {
    target: ParamId,
    velocity_actual: ParamId,
    mode: Option<ParamId>,
    statusword: Option<ParamId>,
    slope: Option<ParamId>,
    torque_actual: Option<ParamId>,
    torque: f64,
    speed: f64,
}

/// The CiA 402 state coding of operation enabled (statusword bits 0-3, 5, 6).
const STATE_MASK: i128 = 0x006F;
const OPERATION_ENABLED: i128 = 0x0027;

impl TorqueLoad {
    /// Present when the description has 6071h and 606Ch.
    pub fn detect(store: &mut Store) -> Option<Self> {
        Some(Self {
            target: object(store, 0x6071, 0)?,
            velocity_actual: object(store, 0x606C, 0)?,
            mode: object(store, 0x6060, 0),
            statusword: object(store, 0x6041, 0),
            slope: object(store, 0x6087, 0),
            torque_actual: object(store, 0x6077, 0),
            torque: 0.0,
            speed: 0.0,
        })
    }

    fn int(store: &Store, id: Option<ParamId>) -> Option<i128> {
        id.and_then(|id| store.int(id))
    }

    /// Whether the drive is operation enabled in profile torque or cyclic synchronous torque
    /// mode.
    fn driving(&self, store: &Store) -> bool {
        let mode = Self::int(store, self.mode)
            .is_some_and(|m| m == PROFILE_TORQUE.into() || m == CYCLIC_SYNC_TORQUE.into());
        let state = Self::int(store, self.statusword).unwrap_or(0) & STATE_MASK;
        mode && state == OPERATION_ENABLED
    }

    /// One step of `h` seconds towards `target` torque.
    fn step(&mut self, target: f64, slope: f64, h: f64) {
        self.torque = if slope > 0.0 {
            self.torque + (target - self.torque).clamp(-slope * h, slope * h)
        } else {
            target
        };
        self.speed += (GAIN * self.torque - FRICTION * self.speed) * h;
    }
}

impl Behaviour for TorqueLoad {
    fn tick(&mut self, store: &mut Store, shared: &mut Shared, dt: Duration) {
        if !self.driving(store) {
            self.torque = 0.0;
            self.speed = 0.0;
            shared.torque_reached = false;
            return;
        }
        let target = store.int(self.target).unwrap_or(0) as f64;
        // In cst each set point is the torque demand at once (the master interpolates; CiA
        // 402-2 cst has no torque slope); profile torque ramps at 6087h.
        let cyclic = Self::int(store, self.mode) == Some(CYCLIC_SYNC_TORQUE.into());
        let slope = if cyclic {
            0.0
        } else {
            Self::int(store, self.slope).unwrap_or(0) as f64
        };
        let mut left = dt.as_secs_f64();
        while left > 0.0 {
            let h = left.min(STEP);
            self.step(target, slope, h);
            left -= h;
        }
        if dt.is_zero() && slope == 0.0 {
            self.torque = target;
        }
        store.set_int(self.velocity_actual, self.speed.round() as i128);
        if let Some(id) = self.torque_actual {
            store.set_int(id, self.torque.round() as i128);
        }
        shared.torque_reached = self.torque == target;
    }

    fn written(&mut self, store: &mut Store, shared: &mut Shared, _id: ParamId) {
        self.tick(store, shared, Duration::ZERO);
    }

    fn reset(&mut self, _store: &mut Store, shared: &mut Shared) {
        self.torque = 0.0;
        self.speed = 0.0;
        shared.torque_reached = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_torque_settles_at_gain_over_friction() {
        let mut load = TorqueLoad {
            target: ParamId::default(),
            velocity_actual: ParamId::default(),
            mode: None,
            statusword: None,
            slope: None,
            torque_actual: None,
            torque: 0.0,
            speed: 0.0,
        };
        for _ in 0..10_000 {
            load.step(10.0, 100.0, STEP);
        }
        assert_eq!(load.torque, 10.0);
        assert!(
            (load.speed - 10.0 * GAIN / FRICTION).abs() < 1.0,
            "{}",
            load.speed
        );
    }
}

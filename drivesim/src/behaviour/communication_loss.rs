//! Communication loss supervision a vendor state machine declares (`[state_machine]
//! communication_loss = { timeout, fault }`): while the motor follows a setpoint, a request must
//! reach the drive within `timeout` (0: off); after a longer silence the drive raises `fault`,
//! which its state machine takes like any fault (Lafert: alarm 0x7521, the motor coasts, Modbus
//! manual lines 809, 1276-1279).

use std::time::Duration;

use drivegen::ir::per_second;

use super::{Behaviour, Motion, Shared};
use crate::store::{ParamId, Store};

/// The supervision and the silence it has counted.
#[derive(Debug)]
pub struct CommunicationLoss {
    timeout: ParamId,
    /// Units of `timeout` per second.
    per_second: f64,
    fault: u16,
    silent: Duration,
}

impl CommunicationLoss {
    /// Present when the description's state machine declares one whose timeout the store holds.
    pub fn detect(store: &Store) -> Option<Self> {
        let loss = store
            .device()
            .state_machine
            .as_ref()?
            .communication_loss
            .clone()?;
        let timeout = store.id(&loss.timeout)?;
        let per_second = per_second(store.parameter(timeout).unit.as_deref()?)?;
        Some(Self {
            timeout,
            per_second,
            fault: loss.fault,
            silent: Duration::ZERO,
        })
    }

    /// The time allowed without a request, `None` while switched off (0).
    fn allowed(&self, store: &Store) -> Option<Duration> {
        let value = store.int(self.timeout).unwrap_or(0);
        (value > 0).then(|| Duration::from_secs_f64(value as f64 / self.per_second))
    }
}

impl Behaviour for CommunicationLoss {
    fn heard(&mut self) {
        self.silent = Duration::ZERO;
    }

    fn written(&mut self, _store: &mut Store, _shared: &mut Shared, _id: ParamId) {
        self.silent = Duration::ZERO;
    }

    /// Counts silence only while the motor runs ("when the motor is running", line 809).
    fn tick(&mut self, store: &mut Store, shared: &mut Shared, dt: Duration) {
        let running = matches!(shared.motion, Motion::Following(_));
        let Some(allowed) = self
            .allowed(store)
            .filter(|_| running && shared.fault.is_none())
        else {
            self.silent = Duration::ZERO;
            return;
        };
        self.silent += dt;
        if self.silent > allowed {
            self.silent = Duration::ZERO;
            shared.fault = Some(self.fault);
        }
    }

    fn reset(&mut self, _store: &mut Store, _shared: &mut Shared) {
        self.silent = Duration::ZERO;
    }
}

//! The write lock and serial watchdog a description declares (`[lock]`, `[[unlock]]`,
//! `[watchdog]`): writes to a parameter of a scope are refused with the lock's exception code
//! until an unlock opening the scope is granted (its grant parameter written with its value, or
//! with the current value of its password parameter, while its requirement holds). An unlock
//! ends on the events it lists that the simulator observes: the lock command, its required
//! parameter changing to another value, a restart (power-down) and the watchdog's timeout, after
//! which the drive does what the action parameter's value maps to (coast, quick stop, a fault).

use std::time::Duration;

use drivegen::ir::{GrantKey, Lock, TimeoutEffect, Unlock, UnlockEnd};

use super::{Behaviour, Halt, Motion, Shared};
use crate::refusal::Refusal;
use crate::store::{ParamId, Store};

/// The lock state of a simulated drive.
#[derive(Debug)]
pub struct WriteLock {
    lock: Lock,
    command: ParamId,
    /// Each gated parameter and the scope it is in.
    gated: Vec<(ParamId, String)>,
    /// Indices into `lock.unlocks` of the unlocks in force.
    active: Vec<usize>,
    /// Those of them whose requirement was lost: the scopes it guards are closed.
    requirement_lost: Vec<usize>,
    /// Time since the drive last heard a request, while unlocked.
    silent: Duration,
}

impl WriteLock {
    /// Present when the description declares a lock whose command is a parameter.
    pub fn detect(store: &Store) -> Option<Self> {
        let device = store.device();
        let lock = device.lock.clone()?;
        let command = store.id(&lock.command)?;
        let gated = device
            .parameters
            .iter()
            .filter_map(|p| {
                let scope = lock.scope_of(p)?;
                Some((store.id(&p.name)?, scope.name.clone()))
            })
            .collect();
        Some(Self {
            lock,
            command,
            gated,
            active: Vec::new(),
            requirement_lost: Vec::new(),
            silent: Duration::ZERO,
        })
    }

    /// Whether an unlock in force opens `scope`.
    fn open(&self, scope: &str) -> bool {
        self.active.iter().any(|&u| {
            let unlock = &self.lock.unlocks[u];
            let closed = self.requirement_lost.contains(&u)
                && unlock
                    .requires
                    .as_ref()
                    .is_some_and(|r| r.scopes.iter().any(|s| s == scope));
            unlock.allows.iter().any(|a| a == scope) && !closed
        })
    }

    fn value_of(store: &Store, name: &str) -> Option<i128> {
        store.int(store.id(name)?)
    }

    /// Whether writing `written` to `id` grants `unlock` now.
    fn grants(store: &Store, unlock: &Unlock, id: ParamId, written: Option<i128>) -> bool {
        if store.id(&unlock.grant.parameter) != Some(id) {
            return false;
        }
        let key = match &unlock.grant.key {
            GrantKey::Value(v) => Some(i128::from(*v)),
            GrantKey::Password(p) => Self::value_of(store, p),
        };
        let required = unlock.requires.as_ref().is_none_or(|r| {
            Self::value_of(store, &r.parameter)
                .is_some_and(|v| r.values.iter().any(|a| i128::from(*a) == v))
        });
        key.is_some() && key == written && required
    }

    /// Ends every unlock in force that lists `event`.
    fn end(&mut self, event: UnlockEnd) {
        let unlocks = &self.lock.unlocks;
        self.active.retain(|&u| !unlocks[u].ends.contains(&event));
        let active = &self.active;
        self.requirement_lost.retain(|u| active.contains(u));
    }

    /// Closes the scopes guarded by the requirements `id` held and no longer holds.
    fn check_requirements(&mut self, store: &Store, id: ParamId) {
        let unlocks = &self.lock.unlocks;
        let lost = self.active.iter().copied().filter(|&u| {
            let unlock = &unlocks[u];
            let lost = unlock.requires.as_ref().is_some_and(|r| {
                store.id(&r.parameter) == Some(id)
                    && !store
                        .int(id)
                        .is_some_and(|v| r.values.iter().any(|a| i128::from(*a) == v))
            });
            lost && unlock.ends.contains(&UnlockEnd::RequirementLost)
        });
        let lost: Vec<usize> = lost.collect();
        for u in lost {
            if !self.requirement_lost.contains(&u) {
                self.requirement_lost.push(u);
            }
        }
    }

    /// The watchdog's timeout and what it does now, if it is armed.
    fn watchdog(&self, store: &Store) -> Option<(Duration, TimeoutEffect)> {
        let w = self.lock.watchdog.as_ref()?;
        let ms = u64::try_from(Self::value_of(store, &w.timeout)?).ok()?;
        let action = Self::value_of(store, &w.action)?;
        let effect = w
            .actions
            .iter()
            .find(|a| i128::from(a.value) == action)?
            .does;
        (effect != TimeoutEffect::Disabled).then_some((Duration::from_millis(ms), effect))
    }

    /// The timeout: the unlocks end, and the action applies if an unlock of its scopes was on.
    fn time_out(&mut self, shared: &mut Shared, effect: TimeoutEffect) {
        let acts = self.lock.watchdog.as_ref().is_some_and(|w| {
            w.acts_with.is_empty() || w.acts_with.iter().any(|scope| self.open(scope))
        });
        self.end(UnlockEnd::SerialTimeout);
        if !acts {
            return;
        }
        match effect {
            TimeoutEffect::Coast => {
                shared.motion = Motion::Disabled;
                shared.halt = Some(Halt::Coast);
            }
            TimeoutEffect::QuickStop => {
                shared.motion = Motion::QuickStop;
                shared.halt = Some(Halt::QuickStop);
            }
            TimeoutEffect::Fault(code) => shared.fault = Some(code),
            TimeoutEffect::Disabled => {}
        }
    }
}

impl Behaviour for WriteLock {
    /// A gated parameter is written only while an unlock opens its scope.
    fn accept(&self, _store: &Store, id: ParamId, _bytes: &[u8]) -> Result<(), Refusal> {
        match self.gated.iter().find(|(g, _)| *g == id) {
            Some((_, scope)) if !self.open(scope) => Err(Refusal::Locked {
                exception: self.lock.refusal,
            }),
            _ => Ok(()),
        }
    }

    fn written(&mut self, store: &mut Store, _shared: &mut Shared, id: ParamId) {
        if id == self.command {
            self.end(UnlockEnd::Lock);
            return;
        }
        self.check_requirements(store, id);
        let written = store.int(id);
        for (u, unlock) in self.lock.unlocks.iter().enumerate() {
            if !Self::grants(store, unlock, id, written) {
                continue;
            }
            self.requirement_lost.retain(|&lost| lost != u);
            if !self.active.contains(&u) {
                self.active.push(u);
            }
        }
        self.silent = Duration::ZERO;
    }

    fn heard(&mut self) {
        self.silent = Duration::ZERO;
    }

    /// The watchdog runs only while unlocked (smd line 376).
    fn tick(&mut self, store: &mut Store, shared: &mut Shared, dt: Duration) {
        if self.active.is_empty() {
            self.silent = Duration::ZERO;
            return;
        }
        let Some((timeout, effect)) = self.watchdog(store) else {
            return;
        };
        self.silent += dt;
        if self.silent > timeout {
            self.silent = Duration::ZERO;
            self.time_out(shared, effect);
        }
    }

    fn reset(&mut self, _store: &mut Store, _shared: &mut Shared) {
        self.end(UnlockEnd::PowerDown);
        self.silent = Duration::ZERO;
    }
}

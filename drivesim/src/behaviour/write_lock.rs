//! The write lock and serial watchdog a description declares (`[lock]`, `[[unlock]]`,
//! `[watchdog]`): writes to a parameter of a scope are refused with the lock's exception code
//! until an unlock opening the scope is granted (its grant parameter written with its value, or
//! with the current value of its password parameter, while its requirement holds). An unlock
//! ends on the events it lists that the simulator observes: the lock command, its required
//! parameter changing to another value, a restart (power-down) and the watchdog's timeout, after
//! which the drive does what the action parameter's value maps to (coast, quick stop, a fault).

use std::time::Duration;

use drivebus::write_lock::UnlockRule;
use drivegen::ir::{GrantKey, Lock, TimeoutEffect, Unlock, UnlockEnd};

use super::{Behaviour, Halt, Motion, Shared};
use crate::refusal::Refusal;
use crate::store::{ParamId, Store};

/// The lock state of a simulated drive.
///
/// Which scope a parameter is in, which scopes an unlock opens, which write grants it and which
/// loses its requirement are the model's rules (`WriteLock::scope_of`, `UnlockRule::opens`,
/// `granted_by`, `requirement_lost_by`) over the table the IR lends (`Device::with_write_lock`),
/// the same table a drive crate holds as `WRITE_LOCK` and its handle follows. What this file
/// adds is what only the drive knows: its password's value, whether a requirement holds when the
/// grant arrives, and the events that end an unlock.
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
        let gated = device.with_write_lock(|view| {
            let gated = device.parameters.iter().filter_map(|p| {
                let scope = view.scope_of(&p.name)?;
                Some((store.id(&p.name)?, scope.name.to_owned()))
            });
            gated.collect()
        })?;
        Some(Self {
            lock,
            command,
            gated,
            active: Vec::new(),
            requirement_lost: Vec::new(),
            silent: Duration::ZERO,
        })
    }

    /// Runs `f` with the rules of the unlocks, in the order of `lock.unlocks`.
    fn with_rules<R>(store: &Store, f: impl FnOnce(&[UnlockRule<'_>]) -> R) -> Option<R> {
        store.device().with_write_lock(|view| f(view.unlocks))
    }

    /// Whether an unlock in force opens `scope`.
    fn open(&self, store: &Store, scope: &str) -> bool {
        Self::with_rules(store, |rules| {
            self.active.iter().any(|&u| {
                let lost = self.requirement_lost.contains(&u);
                rules.get(u).is_some_and(|rule| rule.opens(scope, lost))
            })
        })
        .unwrap_or(false)
    }

    fn value_of(store: &Store, name: &str) -> Option<i128> {
        store.int(store.id(name)?)
    }

    /// Whether the drive takes a grant of `unlock` now, beyond what the model's rule tells a
    /// client: the value written is its password's current value, and its requirement holds.
    fn drive_accepts(store: &Store, unlock: &Unlock, written: i128) -> bool {
        let password = match &unlock.grant.key {
            GrantKey::Value(_) => true,
            GrantKey::Password(p) => Self::value_of(store, p) == Some(written),
        };
        let required = unlock.requires.as_ref().is_none_or(|r| {
            Self::value_of(store, &r.parameter)
                .is_some_and(|v| r.values.iter().any(|a| i128::from(*a) == v))
        });
        password && required
    }

    /// Ends every unlock in force that lists `event`.
    fn end(&mut self, event: UnlockEnd) {
        let unlocks = &self.lock.unlocks;
        self.active.retain(|&u| !unlocks[u].ends.contains(&event));
        let active = &self.active;
        self.requirement_lost.retain(|u| active.contains(u));
    }

    /// Closes the scopes guarded by the requirements the write of `written` to `id` lost.
    fn check_requirements(&mut self, store: &Store, id: ParamId, written: &[u8]) {
        let name = &store.parameter(id).name;
        let lost: Vec<usize> = Self::with_rules(store, |rules| {
            let lost = self.active.iter().copied().filter(|&u| {
                rules
                    .get(u)
                    .is_some_and(|rule| rule.requirement_lost_by(name, written))
            });
            lost.collect()
        })
        .unwrap_or_default();
        for u in lost {
            if !self.requirement_lost.contains(&u) {
                self.requirement_lost.push(u);
            }
        }
    }

    /// The unlocks a write of `written` (`value`, little-endian) to `id` grants.
    fn granted(&self, store: &Store, id: ParamId, value: i128, written: &[u8]) -> Vec<usize> {
        let name = &store.parameter(id).name;
        Self::with_rules(store, |rules| {
            let granted = rules.iter().zip(&self.lock.unlocks).enumerate();
            granted
                .filter(|(_, (rule, unlock))| {
                    rule.granted_by(name, written) && Self::drive_accepts(store, unlock, value)
                })
                .map(|(u, _)| u)
                .collect()
        })
        .unwrap_or_default()
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
    fn time_out(&mut self, store: &Store, shared: &mut Shared, effect: TimeoutEffect) {
        let acts = self.lock.watchdog.as_ref().is_some_and(|w| {
            w.acts_with.is_empty() || w.acts_with.iter().any(|scope| self.open(store, scope))
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
    fn accept(&self, store: &Store, id: ParamId, _bytes: &[u8]) -> Result<(), Refusal> {
        match self.gated.iter().find(|(g, _)| *g == id) {
            Some((_, scope)) if !self.open(store, scope) => Err(Refusal::Locked {
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
        // The value as the rules compare it: all of its bits, so that equal means equal.
        let Some(value) = store.int(id) else {
            self.silent = Duration::ZERO;
            return;
        };
        let written = value.to_le_bytes();
        self.check_requirements(store, id, &written);
        for u in self.granted(store, id, value, &written) {
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
            self.time_out(store, shared, effect);
        }
    }

    fn reset(&mut self, _store: &mut Store, _shared: &mut Shared) {
        self.end(UnlockEnd::PowerDown);
        self.silent = Duration::ZERO;
    }
}

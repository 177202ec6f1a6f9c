//! The IR lends its write lock as the model's [`WriteLock`]: the table generated code holds as
//! `WRITE_LOCK`, the client's lock account follows and the simulated drive decides grants with,
//! built from the description's `[lock]` and `[[unlock]]` in one place.
//!
//! `WriteLock<'a>` borrows nested slices (`LockScope.parameters: &'a [&'a str]`), which an owned
//! IR cannot hand out without keeping references into itself. The view is built for the length
//! of a closure instead: the caller gets `&WriteLock<'_>` and nothing outlives the call (no
//! self-reference, no leak).

use drivebus_model::write_lock::{LockScope, Requirement, UnlockRule, WriteLock};

use super::{Device, GrantKey, Lock, Parameter, UnlockEnd};

impl Device {
    /// Runs `f` with the device's write lock as the model's table, if the device has a lock: each
    /// scope with its parameters resolved (the `rest` scope's too) and the unlocks opening it,
    /// and each unlock with its grant, its key (`None` for a password, which the drive judges)
    /// and the requirement whose loss ends it, when it ends on `requirement_lost`.
    pub fn with_write_lock<R>(&self, f: impl FnOnce(&WriteLock<'_>) -> R) -> Option<R> {
        let lock = self.lock.as_ref()?;
        // Per scope: its parameters, and the unlocks opening it.
        let (members, openers): (Vec<Vec<&str>>, Vec<Vec<&str>>) = lock
            .scopes
            .iter()
            .map(|scope| {
                let members = self.scope_members(&scope.name).map(|p| p.name.as_str());
                let openers = lock.unlocks_opening(&scope.name).map(|u| u.name.as_str());
                (members.collect(), openers.collect())
            })
            .unzip();
        let scopes: Vec<LockScope<'_>> = lock
            .scopes
            .iter()
            .zip(members.iter().zip(&openers))
            .map(|(scope, (parameters, opened_by))| LockScope {
                name: &scope.name,
                parameters,
                opened_by,
            })
            .collect();
        let parts = UnlockParts::of(lock);
        let unlocks: Vec<UnlockRule<'_>> = parts.rules(lock).collect();
        Some(f(&WriteLock {
            command: &lock.command,
            refusal: lock.refusal,
            scopes: &scopes,
            unlocks: &unlocks,
        }))
    }

    /// The parameters in the lock's scope `scope`, in the order of the description.
    pub fn scope_members<'a>(&'a self, scope: &'a str) -> impl Iterator<Item = &'a Parameter> {
        self.parameters
            .iter()
            .filter(move |p| self.lock_scope_of(p).is_some_and(|s| s.name == scope))
    }
}

/// The slices each unlock's rule borrows, one entry per unlock.
struct UnlockParts<'l> {
    opens: Vec<Vec<&'l str>>,
    values: Vec<Vec<i128>>,
    lost_scopes: Vec<Vec<&'l str>>,
}

impl<'l> UnlockParts<'l> {
    fn of(lock: &'l Lock) -> Self {
        let requirement = |u: &'l super::Unlock| u.requires.as_ref();
        Self {
            opens: lock
                .unlocks
                .iter()
                .map(|u| u.allows.iter().map(String::as_str).collect())
                .collect(),
            values: lock
                .unlocks
                .iter()
                .map(|u| {
                    requirement(u).map_or_else(Vec::new, |r| {
                        r.values.iter().copied().map(i128::from).collect()
                    })
                })
                .collect(),
            lost_scopes: lock
                .unlocks
                .iter()
                .map(|u| {
                    requirement(u)
                        .map_or_else(Vec::new, |r| r.scopes.iter().map(String::as_str).collect())
                })
                .collect(),
        }
    }

    fn rules<'v>(&'v self, lock: &'l Lock) -> impl Iterator<Item = UnlockRule<'v>> + 'v
    where
        'l: 'v,
    {
        let borrowed = self.opens.iter().zip(&self.values).zip(&self.lost_scopes);
        lock.unlocks
            .iter()
            .zip(borrowed)
            .map(|(unlock, ((opens, values), lost_scopes))| {
                let key = match &unlock.grant.key {
                    GrantKey::Value(v) => Some(i128::from(*v)),
                    GrantKey::Password(_) => None,
                };
                let lost_without = unlock
                    .requires
                    .as_ref()
                    .filter(|_| unlock.ends.contains(&UnlockEnd::RequirementLost))
                    .map(|r| Requirement {
                        parameter: &r.parameter,
                        values,
                        scopes: lost_scopes,
                    });
                UnlockRule {
                    name: &unlock.name,
                    grant: &unlock.grant.parameter,
                    key,
                    opens,
                    lost_without,
                }
            })
    }
}

#[cfg(test)]
mod tests {
    use crate::ir::{GrantKey, UnlockEnd};

    #[test]
    fn the_view_gates_what_the_lock_gates_and_keeps_each_unlock() {
        let device = crate::test_support::shipped("lenze-smd");
        let lock = device.lock.as_ref().expect("smd has a lock");
        let gated = device.with_write_lock(|view| {
            assert_eq!(view.command, lock.command);
            for p in &device.parameters {
                let ours = device.lock_scope_of(p).map(|s| s.name.as_str());
                assert_eq!(view.scope_of(&p.name).map(|s| s.name), ours, "{}", p.name);
            }
            for (rule, unlock) in view.unlocks.iter().zip(&lock.unlocks) {
                assert_eq!(rule.name, unlock.name);
                let password = matches!(unlock.grant.key, GrantKey::Password(_));
                assert_eq!(rule.key.is_none(), password);
                let ends_on_loss = unlock.ends.contains(&UnlockEnd::RequirementLost);
                assert_eq!(
                    rule.lost_without.is_some(),
                    ends_on_loss && unlock.requires.is_some()
                );
            }
            view.scopes
                .iter()
                .map(|s| s.parameters.len())
                .sum::<usize>()
        });
        assert!(
            gated.is_some_and(|n| n > 0),
            "the smd lock gates parameters"
        );
    }
}

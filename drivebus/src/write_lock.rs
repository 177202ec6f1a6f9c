//! A drive's write lock as a device handle tracks it (`[lock]` / `[[unlock]]` in a description).
//!
//! Some drives refuse writes until the master unlocks them (Lenze smd, sections 4.5-4.6: #48 or
//! #49 unlock, #1 bit 1 locks, a write while locked is answered with exception 01). Whether the
//! drive is locked cannot be read back (the smd's unlock registers are write-only, lines 274-275,
//! and no status register reports the lock), so the handle keeps its own account of the unlocks
//! that may be in force, from the writes it sends:
//!
//! * a handle opens **locked**: the drive powers up locked, and the first write that does
//!   anything must be an unlock (line 1055);
//! * a write of a grant puts in force every unlock it may have granted: an unlock by value
//!   when the value matches, an unlock by password whatever the value (the password is the
//!   drive's to judge);
//! * a write of the lock command ends every unlock; a write that changes the required
//!   parameter to a value outside the requirement ends the unlocks that end on
//!   `requirement_lost`;
//! * the drive refusing a write with the lock's exception code ends every unlock that opens
//!   the written parameter's scope (the handle cannot see a power-down or a serial timeout; the
//!   drive's refusal tells it).
//!
//! [`crate::Device::write_raw`] refuses a write to a parameter of a scope no unlock in force
//! opens, before sending, with [`crate::WriteRefusal::Locked`]. The account errs towards
//! sending: it refuses only writes the drive would refuse too.

use crate::error::{BusError, WriteRefusal};

pub use drivebus_model::write_lock::{LockScope, Requirement, UnlockRule, WriteLock, MAX_UNLOCKS};

/// The unlocks a handle has sent and not seen end.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LockAccount {
    lock: &'static WriteLock<'static>,
    /// Bit `i` set: `lock.unlocks[i]` may be in force.
    in_force: u32,
    /// Bit `i` set: `lock.unlocks[i]` lost its requirement, which closed its guarded scopes.
    requirement_lost: u32,
}

impl LockAccount {
    /// A freshly opened handle's account: locked, as the drive powers up.
    pub(crate) fn locked(lock: &'static WriteLock<'static>) -> Self {
        Self {
            lock,
            in_force: 0,
            requirement_lost: 0,
        }
    }

    /// Why a write to `parameter` is refused before sending, if no unlock in force opens it.
    pub(crate) fn refusal(&self, parameter: &str) -> Option<WriteRefusal> {
        let scope = self.scope_of(parameter)?;
        (!self.opens(scope)).then_some(WriteRefusal::Locked {
            scope: scope.name,
            opened_by: scope.opened_by,
        })
    }

    /// Follows a write of `bytes` (the raw value, little-endian) to `parameter` and its outcome.
    pub(crate) fn follow(&mut self, parameter: &str, bytes: &[u8], outcome: &Result<(), BusError>) {
        match outcome {
            Ok(()) => self.written(parameter, bytes),
            Err(cause) if self.is_refusal(cause) => self.refused(parameter),
            Err(_) => {}
        }
    }

    /// Whether `cause` is the drive refusing a write as locked (the lock's exception code).
    pub(crate) fn is_refusal(&self, cause: &BusError) -> bool {
        matches!(cause, BusError::ModbusException { code, .. } if code.code() == self.lock.refusal)
    }

    fn scope_of(&self, parameter: &str) -> Option<&'static LockScope<'static>> {
        self.lock.scope_of(parameter)
    }

    fn opens(&self, scope: &LockScope) -> bool {
        self.unlocks().any(|(bit, u)| {
            self.in_force & bit != 0 && u.opens(scope.name, self.requirement_lost & bit != 0)
        })
    }

    /// Each unlock with its bit in `in_force`.
    fn unlocks(&self) -> impl Iterator<Item = (u32, &'static UnlockRule<'static>)> {
        let lock: &'static WriteLock<'static> = self.lock;
        lock.unlocks
            .iter()
            .take(MAX_UNLOCKS)
            .enumerate()
            .map(|(i, u)| (1u32 << i, u))
    }

    fn written(&mut self, parameter: &str, bytes: &[u8]) {
        if parameter == self.lock.command {
            self.in_force = 0;
            return;
        }
        for (bit, unlock) in self.unlocks() {
            if unlock.granted_by(parameter, bytes) {
                self.in_force |= bit;
                self.requirement_lost &= !bit;
            } else if unlock.requirement_lost_by(parameter, bytes) {
                self.requirement_lost |= bit;
            }
        }
    }

    /// The drive refused a write to `parameter` as locked: the unlocks that would have let it
    /// through have ended (all of them, when it refused the lock command itself).
    fn refused(&mut self, parameter: &str) {
        if parameter == self.lock.command {
            self.in_force = 0;
            return;
        }
        let Some(scope) = self.scope_of(parameter) else {
            return;
        };
        for (bit, unlock) in self.unlocks() {
            if unlock.opens.contains(&scope.name) {
                self.in_force &= !bit;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modbus::ExceptionCode;

    /// The smd's lock (descriptions/lenze-smd/device.toml), cut to two parameters a scope.
    static SMD: WriteLock = WriteLock {
        command: "lock_security",
        refusal: 0x01,
        scopes: &[
            LockScope {
                name: "controls",
                parameters: &["start", "serial_speed_command"],
                opened_by: &["controls", "all"],
            },
            LockScope {
                name: "parameters",
                parameters: &["acceleration_time", "control_source"],
                opened_by: &["all", "parameter_writing"],
            },
        ],
        unlocks: &[
            UnlockRule {
                name: "controls",
                grant: "unlock_commands",
                key: Some(0),
                opens: &["controls"],
                lost_without: Some(Requirement {
                    parameter: "control_source",
                    values: &[10, 11],
                    scopes: &["controls"],
                }),
            },
            UnlockRule {
                name: "all",
                grant: "unlock_commands",
                key: None,
                opens: &["controls", "parameters"],
                lost_without: Some(Requirement {
                    parameter: "control_source",
                    values: &[10, 11],
                    scopes: &["controls"],
                }),
            },
            UnlockRule {
                name: "parameter_writing",
                grant: "unlock_parameters",
                key: None,
                opens: &["parameters"],
                lost_without: None,
            },
        ],
    };

    fn sent(account: &mut LockAccount, parameter: &str, value: u16) {
        account.follow(parameter, &value.to_le_bytes(), &Ok(()));
    }

    fn open(account: &LockAccount, parameter: &str) -> bool {
        account.refusal(parameter).is_none()
    }

    #[test]
    fn a_new_handle_is_locked_and_names_the_scope_and_its_unlocks() {
        let account = LockAccount::locked(&SMD);
        assert_eq!(
            account.refusal("start"),
            Some(WriteRefusal::Locked {
                scope: "controls",
                opened_by: &["controls", "all"],
            })
        );
        assert!(!open(&account, "acceleration_time"));
        assert!(open(&account, "unlock_commands"), "a grant is never locked");
        assert!(open(&account, "lock_security"), "nor is the lock command");
    }

    #[test]
    fn a_grant_opens_what_it_may_have_granted_and_the_lock_closes_all() {
        let mut account = LockAccount::locked(&SMD);
        sent(&mut account, "unlock_parameters", 123);
        assert!(open(&account, "acceleration_time"));
        assert!(!open(&account, "start"), "#49 does not open the controls");
        sent(&mut account, "lock_security", 2);
        assert!(!open(&account, "acceleration_time"));
        // #48 = 0: the controls unlock, or the password unlock if the password is 0.
        sent(&mut account, "unlock_commands", 0);
        assert!(open(&account, "start") && open(&account, "acceleration_time"));
    }

    #[test]
    fn losing_the_requirement_ends_only_the_unlocks_that_end_on_it() {
        let mut account = LockAccount::locked(&SMD);
        sent(&mut account, "unlock_commands", 0);
        sent(&mut account, "unlock_parameters", 0);
        sent(&mut account, "control_source", 11);
        assert!(open(&account, "start"), "11 keeps the requirement");
        sent(&mut account, "control_source", 8);
        assert!(!open(&account, "start"));
        assert!(
            open(&account, "acceleration_time"),
            "#49 does not end on C01"
        );
    }

    #[test]
    fn losing_the_requirement_closes_only_the_scopes_it_guards() {
        // #48 = C94 opens both; a C01 change ends the controls (line 414) and, as the manual
        // does not say it ends the parameters, they stay open (the account errs to sending).
        let mut account = LockAccount::locked(&SMD);
        sent(&mut account, "unlock_commands", 123);
        sent(&mut account, "control_source", 8);
        assert!(!open(&account, "start"));
        assert!(open(&account, "acceleration_time"));
        sent(&mut account, "control_source", 11);
        assert!(!open(&account, "start"), "a C01 back at 11 does not unlock");
        sent(&mut account, "unlock_commands", 123);
        assert!(open(&account, "start"), "a new grant does");
    }

    #[test]
    fn the_drives_refusal_ends_the_unlocks_of_the_refused_scope() {
        let mut account = LockAccount::locked(&SMD);
        sent(&mut account, "unlock_commands", 7);
        let locked = Err(BusError::ModbusException {
            function: 0x06,
            code: ExceptionCode::from(0x01),
        });
        account.follow("acceleration_time", &10u16.to_le_bytes(), &locked);
        assert!(!open(&account, "acceleration_time"), "a wrong password");
        assert!(!open(&account, "start"), "the password unlock opened both");
        sent(&mut account, "unlock_commands", 0);
        let other = Err(BusError::ModbusException {
            function: 0x06,
            code: ExceptionCode::from(0x03),
        });
        account.follow("start", &8u16.to_le_bytes(), &other);
        assert!(
            open(&account, "start"),
            "another exception says nothing of the lock"
        );
        account.follow("lock_security", &2u16.to_le_bytes(), &locked);
        assert!(!open(&account, "start"), "a refused lock: locked already");
    }
}

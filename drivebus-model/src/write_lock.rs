//! A drive's write lock as a description declares it (`[lock]` / `[[unlock]]`): the command that
//! locks, the scopes of parameters an unlock opens together, and the ways of unlocking.
//!
//! Some drives refuse writes until the master unlocks them (Lenze smd, sections 4.5-4.6: #48 or
//! #49 unlock, #1 bit 1 locks, a write while locked is answered with exception 01). This module
//! is the table only; a client's account of the unlocks it has sent is `drivebus::write_lock`.

/// The most unlocks a lock may declare: the handle keeps the unlocks in force in one `u32`.
pub const MAX_UNLOCKS: usize = 32;

/// A drive's write lock, generated from its description (`WRITE_LOCK` in a drive crate).
#[derive(Debug)]
pub struct WriteLock {
    /// The command parameter whose write locks the drive.
    pub command: &'static str,
    /// The Modbus exception code the drive answers a write with while locked.
    pub refusal: u8,
    /// The groups of parameters an unlock opens together.
    pub scopes: &'static [LockScope],
    /// The ways of unlocking (at most [`MAX_UNLOCKS`]).
    pub unlocks: &'static [UnlockRule],
}

/// Parameters an unlock opens together.
#[derive(Debug)]
pub struct LockScope {
    /// The scope's name in the description.
    pub name: &'static str,
    /// Its parameters (the `rest` resolved to names).
    pub parameters: &'static [&'static str],
    /// The unlocks that open it, by name.
    pub opened_by: &'static [&'static str],
}

/// One way of unlocking, as far as the handle can follow it.
#[derive(Debug)]
pub struct UnlockRule {
    /// The unlock's name in the description.
    pub name: &'static str,
    /// The parameter whose write unlocks.
    pub grant: &'static str,
    /// The raw value that unlocks; `None` for a password, which the drive checks.
    pub key: Option<i128>,
    /// The scopes it opens, by name.
    pub opens: &'static [&'static str],
    /// The requirement whose loss ends it, if it ends on `requirement_lost`.
    pub lost_without: Option<Requirement>,
}

/// A parameter's raw values an unlock needs to stay in force.
#[derive(Debug)]
pub struct Requirement {
    /// The required parameter.
    pub parameter: &'static str,
    /// The raw values that keep the unlock.
    pub values: &'static [i128],
    /// The scopes its loss closes (Lenze smd: a C01 change ends the controls, line 414; what it
    /// does to the parameters is not written, so they stay open).
    pub scopes: &'static [&'static str],
}

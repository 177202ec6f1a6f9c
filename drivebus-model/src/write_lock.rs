//! A drive's write lock as a description declares it (`[lock]` / `[[unlock]]`): the command that
//! locks, the scopes of parameters an unlock opens together, and the ways of unlocking.
//!
//! Some drives refuse writes until the master unlocks them (Lenze smd, sections 4.5-4.6: #48 or
//! #49 unlock, #1 bit 1 locks, a write while locked is answered with exception 01). This module
//! is the table only; a client's account of the unlocks it has sent is `drivebus::write_lock`.

/// The most unlocks a lock may declare: the handle keeps the unlocks in force in one `u32`.
pub const MAX_UNLOCKS: usize = 32;

/// A drive's write lock, generated from its description (`WRITE_LOCK` in a drive crate, a
/// `WriteLock<'static>`), or lent by a tool's own model of a description.
#[derive(Debug)]
pub struct WriteLock<'a> {
    /// The command parameter whose write locks the drive.
    pub command: &'a str,
    /// The Modbus exception code the drive answers a write with while locked.
    pub refusal: u8,
    /// The groups of parameters an unlock opens together.
    pub scopes: &'a [LockScope<'a>],
    /// The ways of unlocking (at most [`MAX_UNLOCKS`]).
    pub unlocks: &'a [UnlockRule<'a>],
}

/// Parameters an unlock opens together.
#[derive(Debug)]
pub struct LockScope<'a> {
    /// The scope's name in the description.
    pub name: &'a str,
    /// Its parameters (the `rest` resolved to names).
    pub parameters: &'a [&'a str],
    /// The unlocks that open it, by name.
    pub opened_by: &'a [&'a str],
}

/// One way of unlocking, as far as the handle can follow it.
#[derive(Debug)]
pub struct UnlockRule<'a> {
    /// The unlock's name in the description.
    pub name: &'a str,
    /// The parameter whose write unlocks.
    pub grant: &'a str,
    /// The raw value that unlocks; `None` for a password, which the drive checks.
    pub key: Option<i128>,
    /// The scopes it opens, by name.
    pub opens: &'a [&'a str],
    /// The requirement whose loss ends it, if it ends on `requirement_lost`.
    pub lost_without: Option<Requirement<'a>>,
}

/// A parameter's raw values an unlock needs to stay in force.
#[derive(Debug)]
pub struct Requirement<'a> {
    /// The required parameter.
    pub parameter: &'a str,
    /// The raw values that keep the unlock.
    pub values: &'a [i128],
    /// The scopes its loss closes (Lenze smd: a C01 change ends the controls, line 414; what it
    /// does to the parameters is not written, so they stay open).
    pub scopes: &'a [&'a str],
}

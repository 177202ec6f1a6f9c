//! Writes a drive refuses until it is unlocked (`[lock]`, `[[unlock]]`) and its serial watchdog
//! (`[watchdog]`). Lenze smd: #48 = 0 unlocks the controls, #48 or #49 = the password C94 the
//! parameters too, #1 bit 1 locks, and a write while locked is answered with exception 01
//! (section 4.5, lines 405-425); n22 / n23 say what a serial timeout does (section 4.4).

use serde::Serialize;

use super::{Citation, Device, Parameter};
use crate::diagnostic::Span;

/// The drive's write lock: its scopes, the ways to unlock them and the command that locks.
#[derive(Debug, Clone, Serialize)]
pub struct Lock {
    /// The command parameter whose write locks the drive (ends every unlock with `lock`).
    pub command: String,
    /// The Modbus exception code the drive answers a refused write with.
    pub refusal: u8,
    /// Groups of parameters an unlock opens together.
    pub scopes: Vec<LockScope>,
    /// The ways to unlock (`[[unlock]]`).
    pub unlocks: Vec<Unlock>,
    /// The serial watchdog (`[watchdog]`), if the drive has one.
    pub watchdog: Option<Watchdog>,
    /// Documentation.
    pub doc: Option<String>,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// Parameters an unlock opens together.
#[derive(Debug, Clone, Serialize)]
pub struct LockScope {
    /// Name; unlocks list it in `allows`.
    pub name: String,
    /// The parameters in it.
    pub parameters: Vec<String>,
    /// Whether it also holds every other writable parameter (except the lock command, the
    /// grants and the other scopes' parameters).
    pub rest: bool,
    /// Documentation.
    pub doc: Option<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// One way of unlocking: a write of a value (or the password) to a grant parameter.
#[derive(Debug, Clone, Serialize)]
pub struct Unlock {
    /// Name: the generated handle method is `unlock_<name>`.
    pub name: String,
    /// The write that unlocks.
    pub grant: Grant,
    /// The scopes it opens.
    pub allows: Vec<String>,
    /// A value the drive must hold for the unlock to be possible, if any.
    pub requires: Option<Requirement>,
    /// The events that end it.
    pub ends: Vec<UnlockEnd>,
    /// Documentation.
    pub doc: Option<String>,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// The write that unlocks: `parameter` written with a fixed value or the drive's password.
#[derive(Debug, Clone, Serialize)]
pub struct Grant {
    /// The parameter written.
    pub parameter: String,
    /// What is written.
    pub key: GrantKey,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// What a grant writes.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GrantKey {
    /// This raw value.
    Value(i64),
    /// The current value of this (password) parameter, which the caller supplies.
    Password(String),
}

/// A value a parameter must hold for an unlock to be possible.
#[derive(Debug, Clone, Serialize)]
pub struct Requirement {
    /// The parameter read.
    pub parameter: String,
    /// Its raw values that allow the unlock.
    pub values: Vec<i64>,
    /// The scopes whose unlock ends when the requirement is lost (`requirement_lost`): those
    /// the manual ties to it, by default every scope the unlock allows.
    pub scopes: Vec<String>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// An event that ends an unlock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum UnlockEnd {
    /// The lock command is written.
    Lock,
    /// The required parameter changes to a value outside the requirement.
    RequirementLost,
    /// The drive powers down (or restarts).
    PowerDown,
    /// The watchdog times out.
    SerialTimeout,
}

impl UnlockEnd {
    /// Every event, with its name in a description.
    pub const ALL: [(&'static str, UnlockEnd); 4] = [
        ("lock", UnlockEnd::Lock),
        ("requirement_lost", UnlockEnd::RequirementLost),
        ("power_down", UnlockEnd::PowerDown),
        ("serial_timeout", UnlockEnd::SerialTimeout),
    ];

    /// Its name in a description.
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(_, end)| *end == self)
            .map_or("", |(name, _)| name)
    }
}

/// The serial watchdog: after `timeout` (ms) without communication while unlocked, the unlock
/// ends and the drive does what the value of `action` says.
#[derive(Debug, Clone, Serialize)]
pub struct Watchdog {
    /// The timeout parameter, in milliseconds.
    pub timeout: String,
    /// The parameter selecting the action.
    pub action: String,
    /// What each value of `action` does.
    pub actions: Vec<TimeoutAction>,
    /// Scopes whose unlock makes a timeout apply its action (empty: any unlock does); other
    /// unlocks only end.
    pub acts_with: Vec<String>,
    /// Documentation.
    pub doc: Option<String>,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// What the drive does on a timeout while `action` holds `value`.
#[derive(Debug, Clone, Serialize)]
pub struct TimeoutAction {
    /// The raw value of the action parameter.
    pub value: i64,
    /// What happens.
    pub does: TimeoutEffect,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

/// A watchdog's reaction to a timeout.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TimeoutEffect {
    /// The watchdog is off: no timeout, nothing ends.
    Disabled,
    /// The power stage turns off; the motor coasts to a stop.
    Coast,
    /// The drive ramps to a stop.
    QuickStop,
    /// The drive trips with this fault code.
    Fault(u16),
}

impl Lock {
    /// Whether `name` is written without any unlock: the lock command and the grants.
    pub fn is_exempt(&self, name: &str) -> bool {
        self.command == name || self.unlocks.iter().any(|u| u.grant.parameter == name)
    }

    /// The scope whose unlock `parameter` needs to be written, if it needs one: the scope that
    /// lists it, else the `rest` scope for any other writable parameter that is not exempt.
    pub fn scope_of(&self, parameter: &Parameter) -> Option<&LockScope> {
        if self.is_exempt(&parameter.name) {
            return None;
        }
        self.scopes
            .iter()
            .find(|s| s.parameters.contains(&parameter.name))
            .or_else(|| {
                parameter
                    .is_writable()
                    .then(|| self.scopes.iter().find(|s| s.rest))
                    .flatten()
            })
    }

    /// The unlocks that open `scope`.
    pub fn unlocks_opening<'a>(&'a self, scope: &'a str) -> impl Iterator<Item = &'a Unlock> {
        self.unlocks
            .iter()
            .filter(move |u| u.allows.iter().any(|a| a == scope))
    }
}

impl Parameter {
    /// Whether any address of the parameter allows writing (and it is not a safety parameter,
    /// which has no plain setter).
    pub fn is_writable(&self) -> bool {
        !self.is_safety()
            && (self.modbus.iter().any(|a| a.access.write)
                || self.canopen.iter().any(|a| a.access.write)
                || self.rs232.iter().any(|a| a.access.write))
    }
}

impl Device {
    /// The scope of the write lock `parameter` needs, if the device has a lock and it needs one.
    pub fn lock_scope_of(&self, parameter: &Parameter) -> Option<&LockScope> {
        self.lock.as_ref()?.scope_of(parameter)
    }
}

//! `[lock]`, `[[unlock]]` and `[watchdog]` as written: which writes a drive refuses until it is
//! unlocked, how it is unlocked and locked, and what its serial watchdog does.

use serde::Deserialize;
use toml::Spanned;

use super::raw::RawCitation;

/// `[lock]`: the drive refuses some writes until unlocked; this command locks it again.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLock {
    pub command: Spanned<String>,
    pub refusal: Spanned<i64>,
    #[serde(default)]
    pub scopes: Vec<Spanned<RawLockScope>>,
    pub doc: Option<String>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `{ name, parameters }` or `{ name, rest = true }`: parameters an unlock opens together.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLockScope {
    pub name: String,
    #[serde(default)]
    pub parameters: Vec<String>,
    #[serde(default)]
    pub rest: bool,
    pub doc: Option<String>,
}

/// `[[unlock]]`: one way of unlocking.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawUnlock {
    pub name: Spanned<String>,
    pub grant: Spanned<RawGrant>,
    pub allows: Spanned<Vec<String>>,
    pub requires: Option<Spanned<RawRequirement>>,
    #[serde(default)]
    pub ends: Vec<Spanned<String>>,
    pub doc: Option<String>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `{ parameter, value }` or `{ parameter, password }`: the write that unlocks.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawGrant {
    pub parameter: String,
    pub value: Option<i64>,
    pub password: Option<String>,
}

/// `{ parameter, values, scopes }`: the unlock is possible only while `parameter` holds one of
/// `values`; losing it ends the unlock of `scopes` (default: all it allows).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRequirement {
    pub parameter: String,
    pub values: Vec<i64>,
    pub scopes: Option<Vec<String>>,
}

/// `[watchdog]`: the drive's serial timeout.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawWatchdog {
    pub timeout: Spanned<String>,
    pub action: Spanned<String>,
    pub actions: Spanned<Vec<Spanned<RawTimeoutAction>>>,
    #[serde(default)]
    pub acts_with: Vec<String>,
    pub doc: Option<String>,
    pub source: Option<Spanned<RawCitation>>,
}

/// `{ value, does, fault }`: what the drive does on a timeout while `action` holds `value`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTimeoutAction {
    pub value: i64,
    pub does: String,
    pub fault: Option<i64>,
}

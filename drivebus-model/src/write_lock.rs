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

impl<'a> WriteLock<'a> {
    /// The scope `parameter` is in, if the lock gates it.
    pub fn scope_of(&self, parameter: &str) -> Option<&'a LockScope<'a>> {
        let scopes: &'a [LockScope<'a>] = self.scopes;
        scopes.iter().find(|s| s.parameters.contains(&parameter))
    }
}

impl UnlockRule<'_> {
    /// Whether this unlock, while in force, opens `scope`: it is one of the scopes it opens, and
    /// not one its lost requirement closed (`requirement_lost`: the required parameter left the
    /// values that keep it).
    pub fn opens(&self, scope: &str, requirement_lost: bool) -> bool {
        let closed_by_loss = requirement_lost
            && self
                .lost_without
                .as_ref()
                .is_some_and(|r| r.scopes.contains(&scope));
        self.opens.contains(&scope) && !closed_by_loss
    }

    /// Whether a write of `bytes` (the raw value, little-endian) to `parameter` may grant this
    /// unlock, as a client can tell: its grant parameter written with its key, or with any value
    /// where the key is a password (the drive judges those).
    pub fn granted_by(&self, parameter: &str, bytes: &[u8]) -> bool {
        self.grant == parameter && self.key.is_none_or(|key| encodes(bytes, key))
    }

    /// Whether a write of `bytes` to `parameter` loses this unlock's requirement: the required
    /// parameter written with a value outside those that keep the unlock.
    pub fn requirement_lost_by(&self, parameter: &str, bytes: &[u8]) -> bool {
        self.lost_without.as_ref().is_some_and(|r| {
            r.parameter == parameter && !r.values.iter().any(|v| encodes(bytes, *v))
        })
    }
}

/// Whether `bytes` (a raw value sent little-endian) hold `value`: the same bits, and nothing of
/// `value` beyond them but its sign extension.
fn encodes(bytes: &[u8], value: i128) -> bool {
    let extension = if value < 0 { 0xFF } else { 0 };
    let held = value.to_le_bytes();
    (0..bytes.len().max(held.len())).all(|i| {
        let value_byte = held.get(i).copied().unwrap_or(extension);
        bytes.get(i).copied().unwrap_or(extension) == value_byte
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const UNLOCK: UnlockRule<'static> = UnlockRule {
        name: "controls",
        grant: "unlock_commands",
        key: Some(-2),
        opens: &["controls", "parameters"],
        lost_without: Some(Requirement {
            parameter: "control_source",
            values: &[1, 2],
            scopes: &["controls"],
        }),
    };

    #[test]
    fn a_grant_is_its_parameter_written_with_its_key_in_any_width() {
        assert!(UNLOCK.granted_by("unlock_commands", &[0xFE, 0xFF]));
        assert!(UNLOCK.granted_by("unlock_commands", &(-2i32).to_le_bytes()));
        assert!(!UNLOCK.granted_by("unlock_commands", &[0xFE, 0x00]));
        assert!(!UNLOCK.granted_by("start", &[0xFE, 0xFF]));
        let password = UnlockRule {
            key: None,
            ..UNLOCK
        };
        assert!(password.granted_by("unlock_commands", &[7]));
    }

    #[test]
    fn a_lost_requirement_closes_only_the_scopes_it_guards() {
        assert!(UNLOCK.requirement_lost_by("control_source", &[3, 0]));
        assert!(!UNLOCK.requirement_lost_by("control_source", &[2, 0]));
        assert!(UNLOCK.opens("parameters", true));
        assert!(!UNLOCK.opens("controls", true));
        assert!(UNLOCK.opens("controls", false));
        assert!(!UNLOCK.opens("elsewhere", false));
    }

    #[test]
    fn values_compare_in_the_width_sent() {
        assert!(encodes(&[0, 0], 0));
        assert!(encodes(&[0xE8, 0x03], 1000));
        assert!(!encodes(&[0xE8, 0x03], 1001));
        assert!(encodes(&[0xFF, 0xFF], -1));
        assert!(!encodes(&[0xFF, 0xFF], 65535 + 65536));
        assert!(encodes(&[0xFF, 0xFF], 65535), "the same bits as -1");
    }
}

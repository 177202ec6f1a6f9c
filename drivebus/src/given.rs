//! Values a drive handle is given when it is opened, which run-time scale expressions read
//! instead of the bus: per-model constants (the product model the user names: Kinco's peak
//! current, ez-Wheel's gear ratio) and scale inputs a protocol cannot read (Kinco's encoder
//! resolution has no Modbus register).

use crate::scale::Ratio;

/// Most named values one handle holds; `drivegen` refuses descriptions that need more.
pub const MAX_GIVEN: usize = 16;

/// A small table of named exact values.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Given {
    entries: [Option<(&'static str, Ratio)>; MAX_GIVEN],
}

impl Given {
    /// The value named `name`, if it was given.
    pub fn get(&self, name: &str) -> Option<Ratio> {
        self.entries
            .iter()
            .flatten()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| *v)
    }

    /// Whether no value was given. Values fill the table from the front and are never removed,
    /// so the first entry tells.
    pub fn is_empty(&self) -> bool {
        self.entries[0].is_none()
    }

    /// Gives (or replaces) the value named `name`. Returns `false`, storing nothing, when the
    /// table already holds [`MAX_GIVEN`] other names.
    pub fn set(&mut self, name: &'static str, value: Ratio) -> bool {
        let slot = match self
            .entries
            .iter()
            .position(|e| e.is_some_and(|(n, _)| n == name))
        {
            Some(at) => Some(at),
            None => self.entries.iter().position(Option::is_none),
        };
        match slot.and_then(|at| self.entries.get_mut(at)) {
            Some(entry) => {
                *entry = Some((name, value));
                true
            }
            None => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_found_by_name_and_replaced() {
        let mut given = Given::default();
        assert_eq!(given.get("peak_current"), None);
        assert!(given.set("peak_current", Ratio::int(45)));
        assert!(given.set("encoder_resolution", Ratio::int(10_000)));
        assert!(given.set("peak_current", Ratio::int(50)));
        assert_eq!(given.get("peak_current"), Some(Ratio::int(50)));
        assert_eq!(given.get("encoder_resolution"), Some(Ratio::int(10_000)));
    }

    #[test]
    fn a_table_is_empty_until_a_value_is_given() {
        let mut given = Given::default();
        assert!(given.is_empty());
        assert!(given.set("peak_current", Ratio::int(45)));
        assert!(!given.is_empty());
        assert!(given.set("peak_current", Ratio::int(50)));
        assert!(!given.is_empty(), "replacing keeps the value");
    }

    #[test]
    fn a_full_table_refuses_new_names() {
        const NAMES: [&str; MAX_GIVEN + 1] = [
            "a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k", "l", "m", "n", "o", "p", "q",
        ];
        let mut given = Given::default();
        for name in &NAMES[..MAX_GIVEN] {
            assert!(given.set(name, Ratio::ONE));
        }
        assert!(!given.set(NAMES[MAX_GIVEN], Ratio::ONE));
        assert_eq!(given.get(NAMES[MAX_GIVEN]), None);
        assert!(
            given.set("a", Ratio::ZERO),
            "an existing name is still replaced"
        );
    }
}

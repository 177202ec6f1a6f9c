//! The identity check on connect (`[identity]` in a description): the parameters that tell the
//! drive's firmware, configuration or product, and the values the description covers. A drive
//! handle's `verify_identity` reads each one its link reaches ([`IdentityChecks`], generated per
//! protocol) and, on a value not covered, refuses every later write before sending
//! ([`WriteRefusal::IdentityMismatch`] or [`WriteRefusal::IdentityOutOfRange`]); reads go on.

use crate::device::Device;
use crate::error::{Error, WriteRefusal};
use crate::link::Link;
use crate::parameter::RawInteger;
use crate::Protocol;

/// The raw values of an identity parameter a description covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Covered {
    /// These values (a firmware release, a vendor-ID, a product code).
    Values(&'static [i128]),
    /// The values from `min` to `max` (a CANopen revision range, 1018h sub 3).
    Range {
        /// The smallest covered value.
        min: i128,
        /// The largest covered value.
        max: i128,
    },
}

impl Covered {
    /// The refusal of writes to a drive whose `parameter` reads `found`, if it is not covered.
    pub fn refusal(&self, parameter: &'static str, found: i128) -> Option<WriteRefusal> {
        match *self {
            Self::Values(expected) if !expected.contains(&found) => {
                Some(WriteRefusal::IdentityMismatch {
                    parameter,
                    expected,
                    found,
                })
            }
            Self::Range { min, max } if !(min..=max).contains(&found) => {
                Some(WriteRefusal::IdentityOutOfRange {
                    parameter,
                    min,
                    max,
                    found,
                })
            }
            Self::Values(_) | Self::Range { .. } => None,
        }
    }
}

/// One identity parameter as protocol `P` reads it, with the values the description covers.
#[derive(Debug, Clone, Copy)]
pub struct IdentityCheck<P: Protocol> {
    /// The identity parameter.
    pub parameter: RawInteger<P>,
    /// The values covered.
    pub covered: Covered,
}

/// The identity checks a drive handle runs over protocol `P`: the `[identity]` parameters `P`
/// reads, in the description's order. Generated for each handle and protocol that reaches one.
pub trait IdentityChecks<P: Protocol> {
    /// The checks, in the order they run.
    const IDENTITY_CHECKS: &'static [IdentityCheck<P>];
}

impl<L: Link> Device<L> {
    /// Reads each identity parameter of `checks` in turn. At the first holding a value not
    /// covered, refuses every later write ([`Device::refuse_writes`]) and returns the refusal
    /// as [`Error::WritesRefused`] naming the parameter, the covered and the found values.
    pub fn verify_identity(&mut self, checks: &[IdentityCheck<L::Protocol>]) -> Result<(), Error> {
        for check in checks {
            let found = self.read_integer(&check.parameter)?;
            self.conclude_identity(check, found)?;
        }
        Ok(())
    }
}

impl<L> Device<L> {
    /// What the blocking and the async `verify_identity` conclude from `found`, the value
    /// `check`'s parameter read: nothing if it is covered; else every later write is refused
    /// and the refusal comes back as [`Error::WritesRefused`] naming the parameter.
    pub(crate) fn conclude_identity<P: Protocol>(
        &mut self,
        check: &IdentityCheck<P>,
        found: i128,
    ) -> Result<(), Error> {
        let parameter = check.parameter.name;
        match check.covered.refusal(parameter, found) {
            Some(reason) => {
                self.refuse_writes(reason);
                Err(Error::WritesRefused { parameter, reason })
            }
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_value_outside_what_is_covered_is_refused() {
        let releases = Covered::Values(&[242, 243]);
        assert_eq!(releases.refusal("fw", 243), None);
        assert_eq!(
            releases.refusal("fw", 241),
            Some(WriteRefusal::IdentityMismatch {
                parameter: "fw",
                expected: &[242, 243],
                found: 241
            })
        );
        let revisions = Covered::Range {
            min: 0x0001_0000,
            max: 0x0001_FFFF,
        };
        assert_eq!(revisions.refusal("revision", 0x0001_0003), None);
        assert!(matches!(
            revisions.refusal("revision", 0x0002_0000),
            Some(WriteRefusal::IdentityOutOfRange {
                found: 0x0002_0000,
                ..
            })
        ));
    }
}

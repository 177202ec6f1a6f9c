//! What the hand-written helpers of this crate report: bus and value failures from `drivebus`,
//! the generated unlock session's refusals ([`UnlockError`]) and writes beyond a bound set by
//! another parameter ([`Error::OutsideBound`]), in one type, each refusal before anything is
//! sent.

use core::fmt;

use drivebus::{Error, WriteRefusal};

use crate::{UnlockError, LOCKED_EXCEPTION};

/// Why a helper of this crate failed.
#[derive(Debug, Clone, PartialEq)]
pub enum SmdError {
    /// A request failed (bus, exception, or a value outside the description's range).
    Bus(Error),
    /// The drive answered a write with exception 0x01, or the handle refused it before sending
    /// (`WriteRefusal::Locked`): it is locked. The unlock ended (a lock, C01 changed,
    /// power-down or a serial timeout; lines 414 and 425) or never happened.
    Locked {
        /// The parameter whose write was refused.
        parameter: &'static str,
    },
    /// Register #50 holds neither 400 nor 507: no register may be written (section 3.3,
    /// line 314). Nothing was sent.
    UnknownConfiguration {
        /// The configuration number the drive reported.
        value: u16,
    },
    /// An unlock's precondition does not hold (C01 must be 10 or 11 to unlock the controls,
    /// line 411). Nothing was sent.
    Requirement {
        /// The parameter read (`control_source`, C01).
        parameter: &'static str,
        /// The raw value it holds.
        found: i128,
        /// The values that allow the unlock.
        allowed: &'static [i128],
    },
    /// A value lies beyond a bound set by another parameter's current value (#40 within
    /// C10...C11, line 501; the description's `bounds`; #40's raw values are 0.1 Hz). Nothing
    /// was sent.
    OutsideBound(drivebus::OutsideBound),
}

impl From<UnlockError> for SmdError {
    fn from(error: UnlockError) -> Self {
        match error {
            UnlockError::Drive(
                Error::WritesRefused {
                    reason: WriteRefusal::UnknownVariant { value, .. },
                    ..
                }
                | Error::VariantUnknown { value, .. },
            ) => Self::UnknownConfiguration {
                value: u16::try_from(value).unwrap_or(u16::MAX),
            },
            UnlockError::Drive(Error::OutsideBound(refusal)) => Self::OutsideBound(refusal),
            UnlockError::Drive(error) => Self::Bus(error),
            UnlockError::Locked { parameter } => Self::Locked { parameter },
            UnlockError::Requirement {
                parameter,
                found,
                allowed,
            } => Self::Requirement {
                parameter,
                found,
                allowed,
            },
        }
    }
}

impl From<Error> for SmdError {
    /// A write refused as locked (exception 0x01, or before sending) becomes
    /// [`SmdError::Locked`]; a write refused, or a moved register not read, because #50 named
    /// no known configuration, [`SmdError::UnknownConfiguration`]; a value beyond a bound,
    /// [`SmdError::OutsideBound`].
    fn from(error: Error) -> Self {
        UnlockError::from(error).into()
    }
}

impl fmt::Display for SmdError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Bus(e) => write!(f, "request failed: {e}"),
            Self::Locked { parameter } => write!(
                f,
                "{parameter}: the drive is locked (exception {LOCKED_EXCEPTION:#04x}); unlock it first (register #48 or #49)"
            ),
            Self::UnknownConfiguration { value } => write!(
                f,
                "parameter configuration (#50) is {value}, not 400 or 507: writing is not attempted"
            ),
            Self::Requirement {
                parameter,
                found,
                allowed,
            } => write!(
                f,
                "{parameter} is {found}; unlocking needs one of {allowed:?} (C01 = 10 or 11 for serial control): nothing was written"
            ),
            Self::OutsideBound(refusal) => write!(f, "{refusal}"),
        }
    }
}

impl core::error::Error for SmdError {}

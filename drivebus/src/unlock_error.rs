//! Why an unlock of a drive's write lock (`[lock]`, `[[unlock]]` in a description), or a write
//! under one, failed: one type for every drive crate, which names it with its lock's refusal
//! code (`pub type UnlockError = drivebus::UnlockError<LOCKED_EXCEPTION>;`).

use core::fmt;

use crate::error::{BusError, Error, WriteRefusal};

/// Why an unlock, or a write under one, failed, for a drive that answers a write while locked
/// with Modbus exception `LOCKED` (Lenze smd: 0x01).
#[derive(Debug, Clone, PartialEq)]
pub enum UnlockError<const LOCKED: u8> {
    /// A request failed (bus, exception, a value outside the description's range or a bound,
    /// or a drive whose configuration the description does not cover).
    Drive(Error),
    /// The drive answered a write with exception `LOCKED`, or the handle refused it before
    /// sending because no unlock sent through it opens the parameter
    /// ([`WriteRefusal::Locked`]): it is locked. The unlock ended (lock, power-down, a serial
    /// timeout, a changed requirement) or never began.
    Locked {
        /// The parameter whose write was refused.
        parameter: &'static str,
    },
    /// The unlock's requirement does not hold; nothing was written.
    Requirement {
        /// The parameter read.
        parameter: &'static str,
        /// Its raw value.
        found: i128,
        /// The raw values that allow the unlock.
        allowed: &'static [i128],
    },
}

impl<const LOCKED: u8> From<Error> for UnlockError<LOCKED> {
    /// A write refused as locked, by the drive with exception `LOCKED` or by the handle before
    /// sending, becomes [`UnlockError::Locked`].
    fn from(error: Error) -> Self {
        match &error {
            Error::Bus {
                parameter,
                cause: BusError::ModbusException { code, .. },
            } if code.code() == LOCKED => Self::Locked { parameter },
            Error::WritesRefused {
                parameter,
                reason: WriteRefusal::Locked { .. },
            } => Self::Locked { parameter },
            _ => Self::Drive(error),
        }
    }
}

impl<const LOCKED: u8> fmt::Display for UnlockError<LOCKED> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Drive(e) => write!(f, "{e}"),
            Self::Locked { parameter } => write!(
                f,
                "{parameter}: the drive is locked (exception {LOCKED:#04x}); unlock it first"
            ),
            Self::Requirement {
                parameter,
                found,
                allowed,
            } => write!(
                f,
                "{parameter} is {found}; unlocking needs one of {allowed:?}: nothing was written"
            ),
        }
    }
}

impl<const LOCKED: u8> core::error::Error for UnlockError<LOCKED> {}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modbus::ExceptionCode;

    type Smd = UnlockError<0x01>;

    fn exception(code: u8) -> Error {
        Error::Bus {
            parameter: "start",
            cause: BusError::ModbusException {
                function: 0x06,
                code: ExceptionCode::from(code),
            },
        }
    }

    #[test]
    fn only_the_locks_own_exception_means_locked() {
        assert_eq!(
            Smd::from(exception(0x01)),
            Smd::Locked { parameter: "start" }
        );
        assert_eq!(Smd::from(exception(0x03)), Smd::Drive(exception(0x03)));
        assert_eq!(
            UnlockError::<0x04>::from(exception(0x01)),
            UnlockError::Drive(exception(0x01))
        );
    }

    #[test]
    fn a_refusal_before_sending_means_locked_too() {
        let refused = Error::WritesRefused {
            parameter: "start",
            reason: WriteRefusal::Locked {
                scope: "controls",
                opened_by: &["controls"],
            },
        };
        assert_eq!(Smd::from(refused), Smd::Locked { parameter: "start" });
        assert_eq!(
            std::format!("{}", Smd::Locked { parameter: "start" }),
            "start: the drive is locked (exception 0x01); unlock it first"
        );
    }
}

//! What the hand-written helpers of this crate report: bus and value failures from `drivebus`, and
//! the refusals the manual's rules call for, each before anything is sent.

use core::fmt;

use drivebus::modbus::ExceptionCode;
use drivebus::{BusError, Error};

use crate::types::ControlSource;
use crate::BoundedWriteError;

/// Exception code an smd answers a write with while it is locked (section 4.5, line 416).
pub const LOCKED_EXCEPTION: ExceptionCode = ExceptionCode::IllegalFunction;

/// Why a helper of this crate failed.
#[derive(Debug, Clone, PartialEq)]
pub enum SmdError {
    /// A request failed (bus, exception, or a value outside the description's range).
    Bus(Error),
    /// The drive answered a write with exception 0x01: it is locked. The unlock ended (a lock,
    /// C01 changed, power-down or a serial timeout; lines 414 and 425) or never happened.
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
    /// C01 is not 10 or 11, so serial control cannot be unlocked (line 411). Nothing was sent.
    NotSerialControl {
        /// The control source C01 holds.
        control_source: ControlSource,
    },
    /// A value lies beyond a bound set by another parameter's current value (#40 within
    /// C10...C11, line 501; the description's `bounds`). Nothing was sent.
    OutsideBound {
        /// The parameter being written.
        parameter: &'static str,
        /// The parameter whose current value is the bound that was broken.
        bound: &'static str,
        /// The raw value asked for (0.1 Hz for #40).
        raw: i128,
        /// The bound's current raw value.
        limit: i128,
    },
}

impl From<BoundedWriteError> for SmdError {
    fn from(error: BoundedWriteError) -> Self {
        match error {
            BoundedWriteError::Drive(error) => error.into(),
            BoundedWriteError::OutsideBound {
                parameter,
                bound,
                raw,
                limit,
            } => Self::OutsideBound {
                parameter,
                bound,
                raw,
                limit,
            },
        }
    }
}

impl From<Error> for SmdError {
    /// A write refused with exception 0x01 becomes [`SmdError::Locked`].
    fn from(error: Error) -> Self {
        match &error {
            Error::Bus {
                parameter,
                cause: BusError::ModbusException { code, .. },
            } if *code == LOCKED_EXCEPTION => Self::Locked { parameter },
            _ => Self::Bus(error),
        }
    }
}

impl fmt::Display for SmdError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Bus(e) => write!(f, "request failed: {e}"),
            Self::Locked { parameter } => write!(
                f,
                "{parameter}: the drive is locked (exception 01); unlock it first (register #48 or #49)"
            ),
            Self::UnknownConfiguration { value } => write!(
                f,
                "parameter configuration (#50) is {value}, not 400 or 507: writing is not attempted"
            ),
            Self::NotSerialControl { control_source } => write!(
                f,
                "C01 is {} ({control_source:?}); serial control needs 10 or 11",
                control_source.raw()
            ),
            Self::OutsideBound {
                parameter,
                bound,
                raw,
                limit,
            } => write!(
                f,
                "{parameter}: raw value {raw} is beyond the current value {limit} of {bound}"
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for SmdError {}

//! Typed errors of the runtime: value conversion, bus failures and protocol rejections.

use core::fmt;

use crate::bound::OutsideBound;
use crate::canopen::sdo::AbortCode;
use crate::interpret::{OutsideRange, RawValue};
use crate::modbus::ExceptionCode;

/// A value could not be converted between its engineering form and its raw wire form.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ValueError {
    /// The value lies outside the range the description declares for the parameter.
    OutOfRange {
        /// Parameter name as in the description.
        parameter: &'static str,
        /// The raw value that was asked for and the allowed range, exactly (an integer as an
        /// integer).
        value: OutsideRange,
    },
    /// The value does not fit the parameter's raw type at all.
    Overflow {
        /// Parameter name as in the description.
        parameter: &'static str,
    },
    /// The value is not a whole multiple of the parameter's scale step; writing it would round.
    NotRepresentable {
        /// Parameter name as in the description.
        parameter: &'static str,
        /// The engineering value that was asked for.
        value: f64,
        /// The smallest step the parameter can express, in engineering units.
        step: f64,
    },
    /// The raw value is not one of the values the description allows (enum or value set).
    NotAllowed {
        /// Parameter name as in the description.
        parameter: &'static str,
        /// The rejected raw value (exactly: an integer as an integer).
        raw: RawValue,
    },
    /// A run-time scale factor evaluated to zero, a division by zero or an overflow.
    BadScale {
        /// Parameter name as in the description.
        parameter: &'static str,
    },
    /// The payload the bus delivered has the wrong length for the parameter's type.
    WrongLength {
        /// Bytes expected.
        expected: usize,
        /// Bytes received.
        actual: usize,
    },
    /// A text value is not valid for its encoding, or longer than its capacity.
    BadText,
}

impl fmt::Display for ValueError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::OutOfRange { parameter, value } => write!(f, "{parameter}: {value}"),
            Self::Overflow { parameter } => write!(f, "{parameter}: value does not fit the raw type"),
            Self::NotRepresentable { parameter, value, step } => write!(
                f,
                "{parameter}: {value} is not a multiple of the parameter's resolution {step}; it would be rounded"
            ),
            Self::NotAllowed { parameter, raw } => {
                write!(f, "{parameter}: raw value {raw} is not one of the allowed values")
            }
            Self::BadScale { parameter } => {
                write!(f, "{parameter}: the run-time scale factor could not be computed")
            }
            Self::WrongLength { expected, actual } => {
                write!(f, "payload has {actual} bytes, the parameter needs {expected}")
            }
            Self::BadText => write!(f, "text is not valid for the parameter's encoding or too long"),
        }
    }
}

/// A failure below the value layer: the bus, the framing or the remote device.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum BusError {
    /// No (valid) answer arrived within the configured time.
    Timeout,
    /// The Modbus device answered with an exception response.
    ModbusException {
        /// Function code of the request.
        function: u8,
        /// Exception code (illegal function, illegal data address, illegal data value, ...).
        code: ExceptionCode,
    },
    /// The CANopen device aborted an SDO transfer.
    SdoAbort {
        /// Object index of the transfer.
        index: u16,
        /// Object subindex of the transfer.
        subindex: u8,
        /// CiA 301 abort code.
        code: AbortCode,
    },
    /// The CANopen client aborted an SDO transfer (toggle or sequence error, unexpected command,
    /// CRC error, buffer too small) and told the server so.
    SdoClientAbort {
        /// Object index of the transfer.
        index: u16,
        /// Object subindex of the transfer.
        subindex: u8,
        /// CiA 301 abort code the client sent.
        code: AbortCode,
    },
    /// A Kinco RS-232 exchange about object `index`:`subindex` failed (bad or out-of-place
    /// telegram, silence, or an error answer).
    Rs232Exchange {
        /// Object index of the request.
        index: u16,
        /// Object subindex of the request.
        subindex: u8,
        /// What went wrong.
        error: crate::rs232::Rs232Error,
    },
    /// A frame arrived but is malformed or does not match the request.
    Frame(&'static str),
    /// The request needs a feature the device does not support (per its description).
    Unsupported(&'static str),
    /// The CAN controller went bus-off: whatever transfer was under way was cut.
    CanBusOff,
    /// The CAN transmit queue stayed full (`ENOBUFS`) through every bounded retry.
    CanQueueFull,
    /// The byte stream ended (the peer closed the connection) under a pending request, or a
    /// request dropped mid-send left a torn frame on it: open a new connection.
    Closed,
    /// The underlying I/O channel failed.
    #[cfg(feature = "std")]
    Io(std::io::ErrorKind),
}

impl fmt::Display for BusError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Timeout => write!(f, "no answer within the timeout"),
            Self::ModbusException { function, code } => {
                write!(f, "Modbus exception {code} to function {function:#04x}")
            }
            Self::SdoAbort {
                index,
                subindex,
                code,
            } => write!(f, "SDO abort {code} on {index:#06x}:{subindex}"),
            Self::SdoClientAbort {
                index,
                subindex,
                code,
            } => write!(
                f,
                "SDO transfer of {index:#06x}:{subindex} aborted by the client with {code}"
            ),
            Self::Rs232Exchange {
                index,
                subindex,
                error,
            } => write!(f, "RS-232 request about {index:#06x}:{subindex}: {error}"),
            Self::Frame(why) => write!(f, "bad frame: {why}"),
            Self::Unsupported(what) => write!(f, "not supported by the device: {what}"),
            Self::CanBusOff => write!(f, "the CAN controller went bus-off"),
            Self::CanQueueFull => write!(f, "the CAN transmit queue stayed full (ENOBUFS)"),
            Self::Closed => write!(
                f,
                "the connection closed, or a dropped request tore a frame"
            ),
            #[cfg(feature = "std")]
            Self::Io(kind) => write!(f, "I/O error: {kind}"),
        }
    }
}

/// Everything a generated accessor can fail with.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// The value could not be converted; nothing was sent.
    Value(ValueError),
    /// The bus or the device failed.
    Bus {
        /// Parameter being accessed, when known.
        parameter: &'static str,
        /// What went wrong.
        cause: BusError,
    },
    /// The parameter does not exist in the drive's selected firmware/configuration variant.
    NotInVariant {
        /// Parameter name as in the description.
        parameter: &'static str,
    },
    /// The drive reported a variant (configuration) its description does not cover, and the
    /// parameter's address depends on the variant: nothing was sent (`set_variant` overrides).
    VariantUnknown {
        /// Parameter name as in the description.
        parameter: &'static str,
        /// The parameter that selects the variant.
        selector: &'static str,
        /// The raw value it holds, which selects no variant.
        value: i128,
    },
    /// The device handle refused the write until the reason is resolved; nothing was sent.
    WritesRefused {
        /// The parameter that was to be written.
        parameter: &'static str,
        /// Why writes are refused.
        reason: WriteRefusal,
    },
    /// The value lies beyond the current value of another parameter that bounds it (`bounds`
    /// in the description, read just before): nothing was written.
    OutsideBound(OutsideBound),
}

/// Why a device handle refuses a write before sending anything: the drive on the other end is
/// not one its description covers, so a described address or scale could be wrong for it (every
/// write is refused), or the parameter is locked (writes to its lock scope are refused until an
/// unlock opens it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum WriteRefusal {
    /// The parameter that tells the drive's configuration holds a value no variant of the
    /// description is selected by (Lenze smd: register #50 neither 400 nor 507).
    UnknownVariant {
        /// The selecting parameter, as in the description.
        selector: &'static str,
        /// The raw value it holds.
        value: i128,
    },
    /// The parameter that tells the drive's firmware or configuration holds a value the
    /// description's `[identity]` does not cover (found by the handle's `verify_identity`).
    IdentityMismatch {
        /// The identity parameter, as in the description.
        parameter: &'static str,
        /// The values the description covers.
        expected: &'static [i128],
        /// The raw value the drive reported.
        found: i128,
    },
    /// An identity parameter the description covers as a range (a CANopen revision range,
    /// 1018h sub 3) holds a value outside it (found by the handle's `verify_identity`).
    IdentityOutOfRange {
        /// The identity parameter, as in the description.
        parameter: &'static str,
        /// The smallest covered value.
        min: i128,
        /// The largest covered value.
        max: i128,
        /// The raw value the drive reported.
        found: i128,
    },
    /// The parameter is in a scope of the drive's write lock (`[lock]`) that no unlock sent
    /// through this handle opens: the drive would refuse the write (Lenze smd: exception 01,
    /// line 416). Unlock first: write a grant (the generated `unlock_<name>` methods do).
    Locked {
        /// The lock scope the parameter is in, as in the description.
        scope: &'static str,
        /// The unlocks that open the scope, as in the description.
        opened_by: &'static [&'static str],
    },
}

impl fmt::Display for WriteRefusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnknownVariant { selector, value } => write!(
                f,
                "{selector} reads {value}, which selects no variant the description covers"
            ),
            Self::IdentityMismatch {
                parameter,
                expected,
                found,
            } => write!(
                f,
                "{parameter} reads {found}; the description covers {expected:?}"
            ),
            Self::IdentityOutOfRange {
                parameter,
                min,
                max,
                found,
            } => write!(
                f,
                "{parameter} reads {found:#x}; the description covers {min:#x}..={max:#x}"
            ),
            Self::Locked { scope, opened_by } => write!(
                f,
                "the drive's `{scope}` parameters are locked; unlock first ({})",
                UnlockNames(opened_by)
            ),
        }
    }
}

/// Unlock names as `a or b`.
struct UnlockNames(&'static [&'static str]);

impl fmt::Display for UnlockNames {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, name) in self.0.iter().enumerate() {
            let separator = if i == 0 { "" } else { " or " };
            write!(f, "{separator}`{name}`")?;
        }
        Ok(())
    }
}

impl Error {
    /// The bus error, if this is one.
    pub fn bus(&self) -> Option<&BusError> {
        match self {
            Self::Bus { cause, .. } => Some(cause),
            _ => None,
        }
    }
}

impl From<ValueError> for Error {
    fn from(e: ValueError) -> Self {
        Self::Value(e)
    }
}

impl From<OutsideBound> for Error {
    fn from(refusal: OutsideBound) -> Self {
        Self::OutsideBound(refusal)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Value(e) => write!(f, "{e}"),
            Self::Bus { parameter, cause } => write!(f, "{parameter}: {cause}"),
            Self::NotInVariant { parameter } => {
                write!(
                    f,
                    "{parameter} does not exist in the drive's selected variant"
                )
            }
            Self::VariantUnknown {
                parameter,
                selector,
                value,
            } => write!(
                f,
                "{parameter} not reached: its address depends on the drive's variant, and \
                 {selector} = {value} selects none the description covers"
            ),
            Self::WritesRefused { parameter, reason } => {
                write!(f, "{parameter} not written: {reason}")
            }
            Self::OutsideBound(refusal) => write!(f, "{refusal}"),
        }
    }
}

// `core::error::Error` (Rust 1.81), so that `no_std` users get `?` into their own error types and
// `&dyn Error` too. Each `Display` already says what the inner error says, so none of them
// returns it again as a `source`.
impl core::error::Error for Error {}
impl core::error::Error for BusError {}
impl core::error::Error for ValueError {}
impl core::error::Error for WriteRefusal {}

// Every build, `no_std` included (`scripts/drivebus-features.sh` checks those), fails to compile
// unless each error is usable as `&dyn core::error::Error`.
const _: [&dyn core::error::Error; 4] = [
    &Error::NotInVariant { parameter: "" },
    &BusError::Timeout,
    &ValueError::BadText,
    &WriteRefusal::Locked {
        scope: "",
        opened_by: &[],
    },
];

impl ValueError {
    /// Names the parameter in an error raised by a codec that did not know it.
    pub fn named(self, name: &'static str) -> Self {
        match self {
            Self::OutOfRange { value, .. } => Self::OutOfRange {
                parameter: name,
                value,
            },
            Self::Overflow { .. } => Self::Overflow { parameter: name },
            Self::NotRepresentable { value, step, .. } => Self::NotRepresentable {
                parameter: name,
                value,
                step,
            },
            Self::NotAllowed { raw, .. } => Self::NotAllowed {
                parameter: name,
                raw,
            },
            Self::BadScale { .. } => Self::BadScale { parameter: name },
            other => other,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every fallible call returns an `Error`, and a drive crate's own errors wrap it (Lafert's
    /// store-and-reset error holds one beside a `Duration`): it must stay well under clippy's
    /// `result_large_err` (128 bytes). Exact raw values cost 16-byte alignment; `OutsideRange`
    /// keeps a value and its range under one tag (three `RawValue`s made `Error` 112 bytes).
    #[test]
    fn an_error_stays_small() {
        let (value, error) = (size_of::<ValueError>(), size_of::<Error>());
        assert!(value <= 80, "ValueError is {value} bytes");
        assert!(error <= 96, "Error is {error} bytes");
    }

    #[test]
    fn errors_are_core_errors_with_their_message() {
        let value = ValueError::Overflow { parameter: "speed" };
        let bus = BusError::Timeout;
        let error = Error::Bus {
            parameter: "speed",
            cause: BusError::Timeout,
        };
        let errors: [&dyn core::error::Error; 3] = [&value, &bus, &error];
        for error in errors {
            assert!(error.source().is_none());
            assert!(!std::format!("{error}").is_empty());
        }
        let refused: &dyn core::error::Error = &Error::OutsideBound(OutsideBound {
            parameter: "speed_setpoint",
            bound: "full_scale_velocity",
            raw: 4501,
            limit: 4500,
        });
        assert_eq!(
            std::format!("{refused}"),
            "speed_setpoint: raw value 4501 is beyond the current value 4500 of full_scale_velocity"
        );
    }
}

//! Why the simulated drive refused a request, and how each protocol says so.

use drivebus::canopen::sdo::AbortCode;
use drivegen::ir::ModbusCaps;

/// A refused read or write, independent of the protocol it arrived on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refusal {
    /// No parameter at this address (Modbus register, CANopen index).
    NoSuchAddress,
    /// The CANopen index exists but not this subindex.
    NoSuchSubindex,
    /// The parameter cannot be written over this protocol.
    ReadOnly,
    /// The parameter cannot be read over this protocol.
    WriteOnly,
    /// Above the described range.
    TooHigh,
    /// Below the described range.
    TooLow,
    /// Not one of the allowed values, or not accepted in the drive's present state.
    InvalidValue,
    /// The payload does not have the parameter's length.
    WrongLength,
    /// The drive is locked: the write needs an unlock first (`[lock]`).
    Locked {
        /// The Modbus exception code the description says the drive answers with.
        exception: u8,
    },
}

impl Refusal {
    /// The Modbus exception code the device answers with, as its description says.
    pub fn modbus_exception(self, caps: Option<&ModbusCaps>) -> u8 {
        let (address, value) = caps.map_or((0x02, 0x03), |c| {
            (c.illegal_address_exception, c.illegal_value_exception)
        });
        match self {
            Refusal::NoSuchAddress | Refusal::NoSuchSubindex => address,
            Refusal::ReadOnly | Refusal::WriteOnly => address,
            Refusal::TooHigh | Refusal::TooLow | Refusal::InvalidValue | Refusal::WrongLength => {
                value
            }
            Refusal::Locked { exception } => exception,
        }
    }

    /// The CiA 301 SDO abort code.
    pub fn sdo_abort(self) -> AbortCode {
        match self {
            Refusal::NoSuchAddress => AbortCode::ObjectDoesNotExist,
            Refusal::NoSuchSubindex => AbortCode::SubindexDoesNotExist,
            Refusal::ReadOnly => AbortCode::ReadOnly,
            Refusal::WriteOnly => AbortCode::WriteOnly,
            Refusal::TooHigh => AbortCode::ValueTooHigh,
            Refusal::TooLow => AbortCode::ValueTooLow,
            Refusal::InvalidValue => AbortCode::InvalidValue,
            Refusal::WrongLength => AbortCode::LengthMismatch,
            Refusal::Locked { .. } => AbortCode::CannotStoreLocalControl,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn access_violations_use_the_standard_codes_without_a_description() {
        assert_eq!(Refusal::ReadOnly.modbus_exception(None), 0x02);
        assert_eq!(Refusal::TooHigh.modbus_exception(None), 0x03);
        assert_eq!(Refusal::ReadOnly.sdo_abort().code(), 0x0601_0002);
        assert_eq!(Refusal::WriteOnly.sdo_abort().code(), 0x0601_0001);
        assert_eq!(Refusal::NoSuchSubindex.sdo_abort().code(), 0x0609_0011);
    }
}

//! What kind of failure a [`BusError`] is, whatever the protocol (as embedded-hal's
//! `ErrorKind`): code above the protocols (a retry policy, a network manager) decides on the
//! kind without matching Modbus, CANopen and RS-232 variants one by one.

use crate::error::BusError;
use crate::rs232::Rs232Error;

/// The kind of a [`BusError`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum BusErrorKind {
    /// No (valid) answer arrived in time: the device may be absent, off or busy.
    Timeout,
    /// The device answered and refused the request (a Modbus exception, an SDO abort, an
    /// RS-232 error answer): asking again the same way gets the same answer.
    Refused,
    /// An answer arrived but broke the protocol (malformed, out of place, wrong checksum,
    /// another station), or the client aborted the transfer for it.
    Protocol,
    /// The request needs something the device or the protocol does not offer.
    Unsupported,
    /// The bus itself failed: the CAN controller went bus-off, or its transmit queue stayed
    /// full.
    Bus,
    /// The operating system's I/O channel failed.
    Io,
}

impl BusError {
    /// The kind of failure, whatever the protocol.
    pub fn kind(&self) -> BusErrorKind {
        match self {
            Self::Timeout => BusErrorKind::Timeout,
            Self::ModbusException { .. } | Self::SdoAbort { .. } => BusErrorKind::Refused,
            Self::SdoClientAbort { .. } | Self::Frame(_) => BusErrorKind::Protocol,
            Self::Rs232Exchange { error, .. } => rs232_kind(error),
            Self::Unsupported(_) => BusErrorKind::Unsupported,
            Self::CanBusOff | Self::CanQueueFull => BusErrorKind::Bus,
            Self::Closed => BusErrorKind::Io,
            #[cfg(feature = "std")]
            Self::Io(_) => BusErrorKind::Io,
        }
    }
}

fn rs232_kind(error: &Rs232Error) -> BusErrorKind {
    match error {
        Rs232Error::Silence | Rs232Error::NoAnswer | Rs232Error::Short { .. } => {
            BusErrorKind::Timeout
        }
        Rs232Error::Refused { .. } => BusErrorKind::Refused,
        Rs232Error::UnsupportedWidth { .. } => BusErrorKind::Unsupported,
        Rs232Error::Checksum { .. }
        | Rs232Error::EchoOutOfPlace
        | Rs232Error::MissingEcho
        | Rs232Error::OtherStation { .. }
        | Rs232Error::OtherObject { .. }
        | Rs232Error::UnexpectedCommand { .. } => BusErrorKind::Protocol,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canopen::sdo::AbortCode;
    use crate::modbus::ExceptionCode;

    #[test]
    fn each_protocol_refusal_is_one_kind() {
        let modbus = BusError::ModbusException {
            function: 0x06,
            code: ExceptionCode::from(0x03),
        };
        let sdo = BusError::SdoAbort {
            index: 0x6040,
            subindex: 0,
            code: AbortCode::from_u32(0x0609_0030),
        };
        let rs232 = BusError::Rs232Exchange {
            index: 0x6040,
            subindex: 0,
            error: Rs232Error::Refused { cause: 0x0609_0030 },
        };
        for refused in [modbus, sdo, rs232] {
            assert_eq!(refused.kind(), BusErrorKind::Refused, "{refused}");
        }
    }

    #[test]
    fn silence_is_a_timeout_on_every_protocol() {
        let rs232 = BusError::Rs232Exchange {
            index: 0x6040,
            subindex: 0,
            error: Rs232Error::Silence,
        };
        assert_eq!(rs232.kind(), BusErrorKind::Timeout);
        assert_eq!(BusError::Timeout.kind(), BusErrorKind::Timeout);
        assert_eq!(BusError::Frame("short").kind(), BusErrorKind::Protocol);
        assert_eq!(BusError::CanBusOff.kind(), BusErrorKind::Bus);
    }
}

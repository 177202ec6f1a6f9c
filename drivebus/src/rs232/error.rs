//! Everything an RS-232 exchange can fail with; [`BusError::Rs232Exchange`](crate::BusError::Rs232Exchange)
//! names the object it was about.

use core::fmt;

/// Why an RS-232 request got no usable answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Rs232Error {
    /// The value has a width the protocol has no command for (it carries 1, 2 or 4 bytes).
    UnsupportedWidth {
        /// The value's width in bytes.
        bytes: usize,
    },
    /// A telegram arrived whose checksum does not match its first nine bytes.
    Checksum {
        /// The checksum byte received.
        received: u8,
        /// The checksum of the nine bytes before it.
        expected: u8,
    },
    /// Fewer than 10 bytes arrived before the timeout: a telegram cut short.
    Short {
        /// Bytes received of the telegram that was due.
        received: usize,
    },
    /// Nothing arrived before the timeout (in multi-point mode: not even the host's own
    /// telegram, so the loop is open).
    Silence,
    /// Multi-point mode: the host's own telegram came back, but no drive answered (no drive has
    /// the station id, or it discarded the telegram, manual line 2220).
    NoAnswer,
    /// The host's own telegram came back where the answer was due: the drive has
    /// `RS232_Loop_Enable` set while the host expects point-to-point, or it came back twice.
    EchoOutOfPlace,
    /// Multi-point mode: another telegram arrived before the host's own came back.
    MissingEcho,
    /// The answer came from another station.
    OtherStation {
        /// The station id in the answer.
        station: u8,
    },
    /// The answer is about another object than the request.
    OtherObject {
        /// Index in the answer.
        index: u16,
        /// Subindex in the answer.
        subindex: u8,
    },
    /// The command byte is not one this exchange can receive (an upload answer to a download,
    /// or no command of the protocol at all).
    UnexpectedCommand {
        /// The command byte received.
        command: u8,
    },
    /// The drive answered with an error (command `80h`).
    Refused {
        /// The error cause, bytes 4–7 of the answer; read as a CiA 301 SDO abort code.
        cause: u32,
    },
}

impl fmt::Display for Rs232Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnsupportedWidth { bytes } => write!(
                f,
                "a {bytes}-byte value cannot be sent (the protocol carries 1, 2 or 4 bytes)"
            ),
            Self::Checksum { received, expected } => write!(
                f,
                "wrong checksum {received:#04x} in the answer (its bytes give {expected:#04x})"
            ),
            Self::Short { received } => {
                write!(f, "answer cut short: {received} of 10 bytes before the timeout")
            }
            Self::Silence => write!(f, "no answer within the timeout"),
            Self::NoAnswer => write!(
                f,
                "the request passed the loop but no drive answered (is the station id in use?)"
            ),
            Self::EchoOutOfPlace => write!(
                f,
                "the request came back where the answer was due (loop mode on the drive but not on the host?)"
            ),
            Self::MissingEcho => write!(
                f,
                "multi-point loop: a telegram arrived before the request came back"
            ),
            Self::OtherStation { station } => write!(f, "answer from station {station}"),
            Self::OtherObject { index, subindex } => {
                write!(f, "answer about another object, {index:#06x}:{subindex}")
            }
            Self::UnexpectedCommand { command } => {
                write!(f, "unexpected command byte {command:#04x}")
            }
            Self::Refused { cause } => {
                let meaning = crate::canopen::sdo::AbortCode::from_u32(*cause).meaning();
                write!(f, "error answer, cause {cause:#010x} ({meaning})")
            }
        }
    }
}

impl core::error::Error for Rs232Error {}

//! Why an SRDO frame, pair or configuration yielded no value.

use core::fmt;
use core::time::Duration;

/// Everything the SRDO consumer, producer and layout checks refuse. No variant carries data from
/// a refused pair: a refused pair never yields a value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum SrdoError {
    /// The inverted frame is not the bitwise complement of the normal frame.
    Inconsistent,
    /// The inverted frame arrived later than SRVT after the normal frame, or not at all.
    SrvtExpired {
        /// Time since the normal frame.
        waited: Duration,
        /// The SRDO valid time.
        srvt: Duration,
    },
    /// No valid pair within the safeguard cycle time.
    SctExpired {
        /// Time since the last valid pair (or since monitoring started).
        since_last: Duration,
        /// The safeguard cycle time.
        sct: Duration,
    },
    /// An inverted frame without a normal frame before it.
    LoneInverted,
    /// A normal frame while the previous normal frame still waited for its inverted frame; the
    /// previous one is dropped and the new one waits.
    LoneNormal,
    /// A frame of the wrong length for the mapping.
    WrongLength {
        /// COB-ID of the frame.
        cob_id: u16,
        /// Bytes the mapping needs.
        expected: u8,
        /// Bytes received.
        actual: u8,
    },
    /// A remote (RTR) frame on an SRDO COB-ID.
    RemoteFrame {
        /// COB-ID of the frame.
        cob_id: u16,
    },
    /// A configuration the SRDO cannot run with (see the message).
    BadConfiguration(&'static str),
}

impl fmt::Display for SrdoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Inconsistent => write!(
                f,
                "SRDO pair disagrees: inverted data is not the complement"
            ),
            Self::SrvtExpired { waited, srvt } => write!(
                f,
                "SRDO inverted frame {} ms after the normal frame, SRVT is {} ms",
                waited.as_millis(),
                srvt.as_millis()
            ),
            Self::SctExpired { since_last, sct } => write!(
                f,
                "no valid SRDO pair for {} ms, SCT is {} ms",
                since_last.as_millis(),
                sct.as_millis()
            ),
            Self::LoneInverted => write!(f, "SRDO inverted frame without its normal frame"),
            Self::LoneNormal => write!(f, "SRDO normal frame without its inverted frame"),
            Self::WrongLength {
                cob_id,
                expected,
                actual,
            } => write!(
                f,
                "SRDO frame {cob_id:#05x} has {actual} bytes, the mapping needs {expected}"
            ),
            Self::RemoteFrame { cob_id } => write!(f, "remote frame on SRDO COB-ID {cob_id:#05x}"),
            Self::BadConfiguration(why) => write!(f, "bad SRDO configuration: {why}"),
        }
    }
}

impl core::error::Error for SrdoError {}

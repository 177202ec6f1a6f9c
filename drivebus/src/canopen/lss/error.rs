//! Why an LSS command failed: the error codes a slave confirms configure commands with (CiA 305),
//! and the master's own failures.

use core::fmt;

use super::Confirmed;
use crate::error::BusError;

/// A configure or store command the slave refused, by its error code (CiA 305).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ConfigureError {
    /// Configure node id, code 1: the node id is out of range.
    NodeIdOutOfRange,
    /// Configure bit timing, code 1: the bit timing is not supported.
    BitTimingNotSupported,
    /// Store configuration, code 1: storing is not supported.
    StoreNotSupported,
    /// Store configuration, code 2: the storage medium could not be accessed.
    StorageAccess,
    /// Code 255: an error the manufacturer defines, with its specific code (byte 2).
    Vendor {
        /// The refused command.
        command: Confirmed,
        /// The manufacturer-specific error code.
        specific: u8,
    },
    /// A code CiA 305 reserves.
    Reserved {
        /// The refused command.
        command: Confirmed,
        /// The error code.
        code: u8,
    },
}

impl ConfigureError {
    /// The verdict `code` (byte 1) and `specific` (byte 2) give on `command`.
    pub fn check(command: Confirmed, code: u8, specific: u8) -> Result<(), Self> {
        Err(match (command, code) {
            (_, 0) => return Ok(()),
            (_, 0xFF) => Self::Vendor { command, specific },
            (Confirmed::NodeId, 1) => Self::NodeIdOutOfRange,
            (Confirmed::BitTiming, 1) => Self::BitTimingNotSupported,
            (Confirmed::Store, 1) => Self::StoreNotSupported,
            (Confirmed::Store, 2) => Self::StorageAccess,
            (command, code) => Self::Reserved { command, code },
        })
    }

    /// The error code and the manufacturer-specific code on the wire.
    pub fn code(self) -> (u8, u8) {
        match self {
            Self::NodeIdOutOfRange | Self::BitTimingNotSupported | Self::StoreNotSupported => {
                (1, 0)
            }
            Self::StorageAccess => (2, 0),
            Self::Vendor { specific, .. } => (0xFF, specific),
            Self::Reserved { code, .. } => (code, 0),
        }
    }
}

impl fmt::Display for ConfigureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NodeIdOutOfRange => {
                f.write_str("the node refused the node id (out of range, code 1)")
            }
            Self::BitTimingNotSupported => {
                f.write_str("the node does not support this bit rate (code 1)")
            }
            Self::StoreNotSupported => {
                f.write_str("the node cannot store its configuration (code 1)")
            }
            Self::StorageAccess => f.write_str("the node could not access its storage (code 2)"),
            Self::Vendor { command, specific } => write!(
                f,
                "the node refused {command:?} with manufacturer-specific code {specific}"
            ),
            Self::Reserved { command, code } => {
                write!(f, "the node refused {command:?} with reserved code {code}")
            }
        }
    }
}

/// Why an LSS command or scan failed.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum LssError {
    /// No slave answered within the timeout.
    NoAnswer,
    /// Several slaves answered a command only one may answer (two nodes with one LSS address,
    /// or several in configuration state): nothing more is sent to them.
    SeveralAnswers,
    /// A node id a configure command cannot carry (0 or 128-254); refused before sending.
    InvalidNodeId(u8),
    /// The slave refused the command, with its error code.
    Refused(ConfigureError),
    /// A Fastscan step a slave had answered went unconfirmed (the node left, or answers
    /// collided): the scan cannot trust the bits found.
    FastscanLost,
    /// The CAN interface failed.
    Bus(BusError),
}

impl From<BusError> for LssError {
    fn from(error: BusError) -> Self {
        Self::Bus(error)
    }
}

impl fmt::Display for LssError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoAnswer => f.write_str("no LSS slave answered within the timeout"),
            Self::SeveralAnswers => f.write_str(
                "several LSS slaves answered a command only one may answer (shared LSS address, or several in configuration state)",
            ),
            Self::InvalidNodeId(id) => {
                write!(f, "node id {id} cannot be configured: expected 1-127 (or 255, none)")
            }
            Self::Refused(error) => error.fmt(f),
            Self::FastscanLost => f.write_str("Fastscan lost its node before the last step"),
            Self::Bus(error) => error.fmt(f),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for LssError {}

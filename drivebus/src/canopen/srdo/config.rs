//! An SRDO's configuration: its communication object (1301h..1340h) and mapping object
//! (1381h..13C0h), as the safety signature and the safety write see them.

use super::SrdoCobIds;
use super::SrdoError;
use super::SrdoTiming;
use crate::canopen::pdo::MappedObject;

/// Information direction (communication sub-index 1; SWD manual lines 1685-1690).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum SrdoDirection {
    /// 00h: the SRDO does not exist (disabled).
    Invalid = 0,
    /// 01h: the node transmits it.
    Transmit = 1,
    /// 02h: the node receives it.
    Receive = 2,
}

impl SrdoDirection {
    /// The direction of a raw sub-index 1 value; 03h..FFh are reserved.
    pub const fn from_u8(raw: u8) -> Option<Self> {
        match raw {
            0 => Some(Self::Invalid),
            1 => Some(Self::Transmit),
            2 => Some(Self::Receive),
            _ => None,
        }
    }
}

/// The communication object of one SRDO (sub-indices 1 to 6), in the object's own units.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SrdoCommunication {
    /// Sub-index 1.
    pub direction: SrdoDirection,
    /// Sub-index 2: safeguard cycle time (refresh time for a producer), ms.
    pub sct_ms: u16,
    /// Sub-index 3: SRDO valid time, ms. The SWD tables declare it U16 (e.g. line 1739); CiA 304
    /// and the SWD's own summary (lines 1670, 3625) make it one byte, and the signature takes one
    /// byte (see [`signature`](super::signature::signature)).
    pub srvt_ms: u16,
    /// Sub-index 4: transmission type (FEh on the SWD, lines 1694-1712).
    pub transmission_type: u8,
    /// Sub-index 5: COB-ID of the normal data.
    pub cob_id_normal: u32,
    /// Sub-index 6: COB-ID of the inverted data.
    pub cob_id_inverted: u32,
}

impl SrdoCommunication {
    /// The COB-IDs as frame identifiers (refused if not 11-bit or marked invalid).
    pub const fn cob_ids(&self) -> Result<SrdoCobIds, SrdoError> {
        SrdoCobIds::from_objects(self.cob_id_normal, self.cob_id_inverted)
    }

    /// SCT and SRVT, checked.
    pub const fn timing(&self) -> Result<SrdoTiming, SrdoError> {
        SrdoTiming::from_millis(self.sct_ms, self.srvt_ms)
    }
}

/// One SRDO: its number and its whole configuration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SrdoConfig<'a> {
    /// SRDO number, 1..=64.
    pub number: u8,
    /// The communication object.
    pub communication: SrdoCommunication,
    /// The mapping object's entries in sub-index order (normal, inverted, normal, ...).
    pub mapping: &'a [MappedObject],
}

/// Highest SRDO number (communication objects 1301h..1340h).
pub const MAX_SRDO: u8 = 64;

impl SrdoConfig<'_> {
    /// The SRDO number, checked against 1..=64.
    pub const fn checked_number(&self) -> Result<u8, SrdoError> {
        if self.number == 0 || self.number > MAX_SRDO {
            return Err(SrdoError::BadConfiguration("SRDO number outside 1..=64"));
        }
        Ok(self.number)
    }

    /// Communication object index: 1300h + number.
    pub const fn communication_index(&self) -> Result<u16, SrdoError> {
        match self.checked_number() {
            Ok(n) => Ok(0x1300 + n as u16),
            Err(e) => Err(e),
        }
    }

    /// Mapping object index: 1380h + number.
    pub const fn mapping_index(&self) -> Result<u16, SrdoError> {
        match self.checked_number() {
            Ok(n) => Ok(0x1380 + n as u16),
            Err(e) => Err(e),
        }
    }
}

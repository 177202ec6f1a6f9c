//! The two COB-IDs of an SRDO: normal data and inverted data.

use super::error::SrdoError;
use crate::canopen::MAX_COB_ID as MAX_ID;

/// The CAN identifiers of an SRDO's two frames (communication sub-indices 5 and 6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SrdoCobIds {
    normal: u16,
    inverted: u16,
}

impl SrdoCobIds {
    /// Two distinct 11-bit identifiers, or [`SrdoError::BadConfiguration`].
    pub const fn new(normal: u16, inverted: u16) -> Result<Self, SrdoError> {
        if normal > MAX_ID || inverted > MAX_ID {
            return Err(SrdoError::BadConfiguration("SRDO COB-ID exceeds 11 bits"));
        }
        if normal == inverted {
            return Err(SrdoError::BadConfiguration(
                "SRDO normal and inverted COB-IDs must differ",
            ));
        }
        Ok(Self { normal, inverted })
    }

    /// The identifiers held in the communication object's 32-bit COB-ID entries; refused if an
    /// entry has bits above the 11-bit identifier (bit 31 "invalid", 29-bit frames).
    pub const fn from_objects(normal: u32, inverted: u32) -> Result<Self, SrdoError> {
        if normal > MAX_ID as u32 || inverted > MAX_ID as u32 {
            return Err(SrdoError::BadConfiguration(
                "SRDO COB-ID entry is marked invalid or is not an 11-bit identifier",
            ));
        }
        Self::new(normal as u16, inverted as u16)
    }

    /// Identifier of the normal-data frame.
    pub const fn normal(&self) -> u16 {
        self.normal
    }

    /// Identifier of the inverted-data frame.
    pub const fn inverted(&self) -> u16 {
        self.inverted
    }
}

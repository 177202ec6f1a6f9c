//! Checking the signature a drive holds (13FFh sub n) against an SRDO configuration: a mismatch
//! is reported with both values.

use core::fmt;

use super::config::SrdoConfig;
use super::safety_write::SIGNATURES;
use super::signature::{verify, VerifyError};
use crate::canopen::address::NodeId;
use crate::canopen::link::SdoBus;
use crate::error::BusError;

/// Why [`check_stored_signature`] failed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum StoredSignatureError {
    /// The configuration cannot be signed, or the drive's signature differs (both values).
    Verify(VerifyError),
    /// Reading 13FFh failed, or it is not two bytes.
    Bus(BusError),
}

impl fmt::Display for StoredSignatureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Verify(e) => e.fmt(f),
            Self::Bus(e) => write!(f, "reading the SRDO signature: {e}"),
        }
    }
}

impl core::error::Error for StoredSignatureError {}

/// Reads SRDO `config.number`'s signature from `node` and compares it with `config`'s.
pub fn check_stored_signature<B: SdoBus + ?Sized>(
    bus: &mut B,
    node: NodeId,
    config: &SrdoConfig<'_>,
) -> Result<(), StoredSignatureError> {
    let mut buf = [0u8; 2];
    let len = bus
        .upload(node, SIGNATURES, config.number, &mut buf)
        .map_err(StoredSignatureError::Bus)?;
    if len != 2 {
        return Err(StoredSignatureError::Bus(BusError::Frame(
            "SRDO signature (13FFh) is not 2 bytes",
        )));
    }
    verify(config, u16::from_le_bytes(buf)).map_err(StoredSignatureError::Verify)
}

//! The two SRDO times: safeguard cycle time (SCT) and SRDO valid time (SRVT).

use core::time::Duration;

use super::error::SrdoError;

/// SCT and SRVT of one SRDO, checked as the SWD manual requires: both non-zero (line 1679) and
/// SRVT below SCT (line 1681).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SrdoTiming {
    sct: Duration,
    srvt: Duration,
}

impl SrdoTiming {
    /// The times, or [`SrdoError::BadConfiguration`] if one is zero or SRVT is not below SCT.
    pub const fn new(sct: Duration, srvt: Duration) -> Result<Self, SrdoError> {
        if sct.is_zero() || srvt.is_zero() {
            return Err(SrdoError::BadConfiguration("SCT and SRVT must not be 0"));
        }
        if srvt.as_nanos() >= sct.as_nanos() {
            return Err(SrdoError::BadConfiguration("SRVT must be lower than SCT"));
        }
        Ok(Self { sct, srvt })
    }

    /// The times as the communication object holds them (sub-indices 2 and 3, milliseconds).
    pub const fn from_millis(sct_ms: u16, srvt_ms: u16) -> Result<Self, SrdoError> {
        Self::new(
            Duration::from_millis(sct_ms as u64),
            Duration::from_millis(srvt_ms as u64),
        )
    }

    /// Safeguard cycle time: the longest gap between two valid pairs (the consumer), the
    /// transmission period (the producer).
    pub const fn sct(&self) -> Duration {
        self.sct
    }

    /// SRDO valid time: the longest gap between the normal frame and its inverted frame.
    pub const fn srvt(&self) -> Duration {
        self.srvt
    }
}

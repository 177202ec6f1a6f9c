//! The SRDO producer: the normal frame and its inverted frame, once per SCT.

use core::time::Duration;

use super::complement::complement;
use super::SrdoCobIds;
use super::SrdoError;
use crate::canopen::frame::CanFrame;

/// The transmitting end of one SRDO. Time is an input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SrdoProducer {
    cob_ids: SrdoCobIds,
    sct: Duration,
    bytes: u8,
    last_sent: Option<Duration>,
}

impl SrdoProducer {
    /// A producer of `bits` bits of normal data (1..=64), sending every `sct`.
    pub const fn new(cob_ids: SrdoCobIds, sct: Duration, bits: u32) -> Result<Self, SrdoError> {
        if bits == 0 || bits > 64 {
            return Err(SrdoError::BadConfiguration("SRDO data must be 1..=64 bits"));
        }
        if sct.is_zero() {
            return Err(SrdoError::BadConfiguration("SCT must not be 0"));
        }
        Ok(Self {
            cob_ids,
            sct,
            bytes: bits.div_ceil(8) as u8,
            last_sent: None,
        })
    }

    /// The two frames carrying `normal` (exactly the mapping's length): normal first, then the
    /// inverted copy.
    pub fn pair(&self, normal: &[u8]) -> Result<[CanFrame; 2], SrdoError> {
        if normal.len() != usize::from(self.bytes) {
            return Err(SrdoError::WrongLength {
                cob_id: self.cob_ids.normal(),
                expected: self.bytes,
                actual: normal.len().min(usize::from(u8::MAX)) as u8,
            });
        }
        let inverted = complement(normal);
        let len = usize::from(self.bytes);
        Ok([
            frame(self.cob_ids.normal(), normal)?,
            frame(self.cob_ids.inverted(), &inverted[..len])?,
        ])
    }

    /// Whether a pair is due at `now`: none sent yet, or SCT elapsed since the last one.
    pub fn is_due(&self, now: Duration) -> bool {
        self.last_sent
            .is_none_or(|last| now.saturating_sub(last) >= self.sct)
    }

    /// The pair for `normal` if one is due at `now` (and records it as sent), else `None`.
    pub fn poll(
        &mut self,
        now: Duration,
        normal: &[u8],
    ) -> Result<Option<[CanFrame; 2]>, SrdoError> {
        if !self.is_due(now) {
            return Ok(None);
        }
        let pair = self.pair(normal)?;
        self.last_sent = Some(now);
        Ok(Some(pair))
    }
}

fn frame(id: u16, data: &[u8]) -> Result<CanFrame, SrdoError> {
    CanFrame::new(id, data).map_err(|_| SrdoError::BadConfiguration("SRDO frame does not fit"))
}

//! The SRDO consumer: releases a value only for a consistent pair received in time.
//!
//! Rules (EN 50325-5 as the SWD manual states them, lines 1659-1681):
//! * the normal frame comes first, its inverted frame after it, within SRVT;
//! * the inverted data is the bitwise complement of the normal data;
//! * both frames have the mapping's length;
//! * consecutive valid pairs are at most SCT apart (measured between their normal frames, and
//!   from [`SrdoConsumer::start`] for the first one).
//!
//! Anything else is an [`SrdoError`] and no value. After an SCT expiry is reported the monitor
//! re-arms at the next valid pair; the application decides what the expiry means (the drive goes
//! to its safe state, EMCY 8201h–8205h).

use core::time::Duration;

use super::complement::is_complement;
use super::SrdoCobIds;
use super::SrdoError;
use super::SrdoTiming;
use crate::canopen::frame::CanFrame;
use crate::canopen::pdo::Payload;

/// A normal frame waiting for its inverted frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Pending {
    data: [u8; 8],
    at: Duration,
}

/// The receiving end of one SRDO. Time is an input: pass the same clock's readings to
/// [`handle`](Self::handle) and [`poll`](Self::poll).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SrdoConsumer {
    cob_ids: SrdoCobIds,
    timing: SrdoTiming,
    bits: u32,
    bytes: u8,
    pending: Option<Pending>,
    sct_from: Option<Duration>,
}

impl SrdoConsumer {
    /// A consumer of `bits` bits of normal data (1..=64; see
    /// [`data_bits`](super::mapping::data_bits)).
    pub const fn new(
        cob_ids: SrdoCobIds,
        timing: SrdoTiming,
        bits: u32,
    ) -> Result<Self, SrdoError> {
        if bits == 0 || bits > 64 {
            return Err(SrdoError::BadConfiguration("SRDO data must be 1..=64 bits"));
        }
        Ok(Self {
            cob_ids,
            timing,
            bits,
            bytes: bits.div_ceil(8) as u8,
            pending: None,
            sct_from: None,
        })
    }

    /// Starts SCT monitoring at `now` (the node entered Operational), so that an SRDO that
    /// never arrives is reported too.
    pub fn start(&mut self, now: Duration) {
        self.sct_from = Some(now);
        self.pending = None;
    }

    /// The identifiers this consumer listens to.
    pub const fn cob_ids(&self) -> SrdoCobIds {
        self.cob_ids
    }

    /// Handles one received frame at `now`. `None` if the frame is not on this SRDO's COB-IDs;
    /// otherwise the released normal data of a valid pair, `Ok(None)` while a normal frame
    /// waits for its inverted frame, or the reason the frame or pair is refused.
    pub fn handle(
        &mut self,
        frame: &CanFrame,
        now: Duration,
    ) -> Option<Result<Option<Payload>, SrdoError>> {
        let id = frame.id();
        if id != self.cob_ids.normal() && id != self.cob_ids.inverted() {
            return None;
        }
        Some(self.checked(frame, now))
    }

    fn checked(&mut self, frame: &CanFrame, now: Duration) -> Result<Option<Payload>, SrdoError> {
        let cob_id = frame.id();
        if frame.is_remote() {
            self.pending = None;
            return Err(SrdoError::RemoteFrame { cob_id });
        }
        if frame.dlc() != self.bytes {
            self.pending = None;
            return Err(SrdoError::WrongLength {
                cob_id,
                expected: self.bytes,
                actual: frame.dlc(),
            });
        }
        if cob_id == self.cob_ids.normal() {
            self.normal(frame, now).map(|()| None)
        } else {
            self.inverted(frame, now).map(Some)
        }
    }

    fn normal(&mut self, frame: &CanFrame, now: Duration) -> Result<(), SrdoError> {
        let previous = self.pending.replace(Pending {
            data: frame.padded(),
            at: now,
        });
        self.check_sct(now)?;
        match previous {
            Some(_) => Err(SrdoError::LoneNormal),
            None => Ok(()),
        }
    }

    fn inverted(&mut self, frame: &CanFrame, now: Duration) -> Result<Payload, SrdoError> {
        let pending = self.pending.take().ok_or(SrdoError::LoneInverted)?;
        let waited = now.saturating_sub(pending.at);
        if waited > self.timing.srvt() {
            return Err(SrdoError::SrvtExpired {
                waited,
                srvt: self.timing.srvt(),
            });
        }
        if !is_complement(&pending.data, frame.data(), self.bits) {
            return Err(SrdoError::Inconsistent);
        }
        self.sct_from = Some(pending.at);
        Ok(Payload::new(pending.data, usize::from(self.bytes)))
    }

    /// Reports an SCT expiry once, then waits for the next valid pair to re-arm.
    fn check_sct(&mut self, now: Duration) -> Result<(), SrdoError> {
        let Some(from) = self.sct_from else {
            return Ok(());
        };
        let since_last = now.saturating_sub(from);
        if since_last > self.timing.sct() {
            self.sct_from = None;
            return Err(SrdoError::SctExpired {
                since_last,
                sct: self.timing.sct(),
            });
        }
        Ok(())
    }

    /// Checks the timers at `now` without a frame: a normal frame whose inverted frame is
    /// overdue (SRVT), or no valid pair for longer than SCT. Each expiry is reported once.
    pub fn poll(&mut self, now: Duration) -> Result<(), SrdoError> {
        if let Some(pending) = self.pending {
            let waited = now.saturating_sub(pending.at);
            if waited > self.timing.srvt() {
                self.pending = None;
                return Err(SrdoError::SrvtExpired {
                    waited,
                    srvt: self.timing.srvt(),
                });
            }
        }
        self.check_sct(now)
    }

    /// The next time [`poll`](Self::poll) could report an expiry, if any timer runs.
    pub fn next_deadline(&self) -> Option<Duration> {
        let srvt = self.pending.map(|p| p.at + self.timing.srvt());
        let sct = self.sct_from.map(|from| from + self.timing.sct());
        match (srvt, sct) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

//! The receive side of SLCAN without I/O: bytes in, events and command answers out. The
//! blocking [`SlcanBus`](super::slcan::SlcanBus) and the async
//! [`AsyncSlcanBus`](super::async_slcan::AsyncSlcanBus) both feed it what their stream reads.

use std::vec::Vec;

use super::slcan::{parse_line, SlcanLine};
use super::{CanErrorReport, CanEvent, Timestamp};
use crate::error::BusError;

/// The adapter's error answer.
pub(crate) const BEL: u8 = 0x07;
/// Longest line the protocol produces (extended frame, 8 bytes, timestamp) with margin.
pub(crate) const MAX_LINE: usize = 64;

/// The answer to a command of the opening sequence.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Answer {
    /// CR: accepted.
    Accepted,
    /// BEL: refused.
    Refused,
}

/// Bytes received from an SLCAN adapter, not yet decoded.
#[derive(Debug, Default)]
pub(crate) struct SlcanDecoder {
    pending: Vec<u8>,
    refused: usize,
}

impl SlcanDecoder {
    /// Adds received bytes. A buffer grown past any line's length without a terminator held
    /// noise: it is dropped first, so decoding resynchronises on the next terminator. Whole
    /// lines kept while a command's answer is awaited stay.
    pub(crate) fn push(&mut self, bytes: &[u8]) {
        let terminated = || {
            self.pending
                .iter()
                .any(|&b| b == b'\r' || b == b'\n' || b == BEL)
        };
        if self.pending.len() > MAX_LINE && !terminated() {
            self.pending.clear();
        }
        self.pending.extend_from_slice(bytes);
    }

    /// Commands and frames the adapter refused (BEL answers) so far.
    pub(crate) fn refused(&self) -> usize {
        self.refused
    }

    /// Takes the answer to a command out of the buffer: a BEL or an empty line (CR alone) at the
    /// start of a line. Whole lines before it (frames, `z`) stay for [`SlcanDecoder::next_event`].
    pub(crate) fn take_answer(&mut self) -> Option<Answer> {
        let mut start = 0;
        while start < self.pending.len() {
            match self.pending[start] {
                BEL => {
                    self.pending.drain(start..=start);
                    return Some(Answer::Refused);
                }
                b'\r' => {
                    self.pending.drain(start..=start);
                    return Some(Answer::Accepted);
                }
                _ => {
                    let end = self.pending[start..].iter().position(|&b| b == b'\r')?;
                    start += end + 1;
                }
            }
        }
        None
    }

    /// Takes one complete line (or BEL) out of the buffer and decodes it; `None` when no whole
    /// line is buffered.
    pub(crate) fn next_event(&mut self) -> Option<Result<CanEvent, BusError>> {
        loop {
            let end = self
                .pending
                .iter()
                .position(|&b| b == b'\r' || b == b'\n' || b == BEL)?;
            if self.pending[end] == BEL {
                // A BEL ends whatever came before it on the line: that part is noise.
                let noise = end > 0;
                self.pending.drain(..=end);
                self.refused += 1;
                if noise {
                    return Some(Ok(CanEvent::Garbage {
                        why: "SLCAN: text before an error answer",
                    }));
                }
                return Some(Ok(CanEvent::Refused));
            }
            let line: Vec<u8> = self.pending.drain(..=end).take(end).collect();
            match parse_line(&line) {
                Ok(SlcanLine::Frame { frame, timestamp }) => {
                    return Some(Ok(CanEvent::Frame {
                        frame,
                        timestamp: timestamp.map(Timestamp::AdapterMillis),
                    }))
                }
                Ok(SlcanLine::Status(flags)) => {
                    return Some(Ok(CanEvent::Error {
                        report: CanErrorReport::from_slcan_status(flags),
                        timestamp: None,
                    }))
                }
                Ok(SlcanLine::Ignored) => {}
                Err(BusError::Frame(why)) => return Some(Ok(CanEvent::Garbage { why })),
                Err(e) => return Some(Err(e)),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_kept_while_an_answer_is_awaited_survive_a_long_wait() {
        let mut decoder = SlcanDecoder::default();
        for _ in 0..10 {
            decoder.push(b"t1238DEADBEEF01020304\r");
            assert_eq!(decoder.take_answer(), None);
        }
        decoder.push(b"\r");
        assert_eq!(decoder.take_answer(), Some(Answer::Accepted));
        let frames = core::iter::from_fn(|| decoder.next_event()).count();
        assert_eq!(frames, 10);
    }

    #[test]
    fn an_unterminated_run_of_noise_is_dropped() {
        let mut decoder = SlcanDecoder::default();
        decoder.push(&[b'x'; MAX_LINE + 1]);
        decoder.push(b"t1230\r");
        assert!(matches!(
            decoder.next_event(),
            Some(Ok(CanEvent::Frame { .. }))
        ));
        assert!(decoder.next_event().is_none());
    }
}

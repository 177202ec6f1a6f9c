//! Modbus RTU: framing with CRC-16, frame scanning that resynchronises after garbage, and the
//! silent intervals t1.5 / t3.5 derived from the line settings.
//!
//! Frames are delimited by content, not by silence: the answer's length follows from the request,
//! and a candidate is accepted only with a valid CRC, the right unit and a PDU that answers the
//! request. A user-space client cannot observe a 750 µs gap inside a frame reliably (USB adapters
//! deliver bytes in 1–16 ms batches), so t1.5 is informational; t3.5 is enforced as the least idle
//! time before each request.

use core::time::Duration;

use crate::error::BusError;

use super::address::UnitId;
use super::crc::{check, crc16_modbus};
use super::framing::{answers, Framing, Scan};
use super::pdu::{function, Request, MAX_PDU};

/// Largest RTU ADU: address, 253-byte PDU, CRC.
pub const MAX_ADU: usize = 1 + MAX_PDU + 2;

/// Encodes `request` to `unit` as an RTU frame into `out`; returns its length.
#[inline]
pub fn encode_request(
    unit: UnitId,
    request: &Request<'_>,
    out: &mut [u8],
) -> Result<usize, BusError> {
    let (head, rest) = out.split_first_mut().ok_or(BusError::Unsupported(
        "output buffer too small for the request",
    ))?;
    *head = unit.0;
    let len = 1 + request.encode(rest)?;
    seal(out, len)
}

/// Appends the CRC to the `len` bytes at the start of `out`; returns the frame length.
#[inline]
pub fn seal(out: &mut [u8], len: usize) -> Result<usize, BusError> {
    if out.len() < len.saturating_add(2) {
        return Err(BusError::Unsupported("output buffer too small for the CRC"));
    }
    let crc = crc16_modbus(&out[..len]).to_le_bytes();
    out[len..len + 2].copy_from_slice(&crc);
    Ok(len + 2)
}

/// Checks an RTU frame's CRC and unit id and returns its PDU.
#[inline]
pub fn open_frame(unit: UnitId, frame: &[u8]) -> Result<&[u8], BusError> {
    if frame.len() < 4 {
        return Err(BusError::Frame("RTU frame too short"));
    }
    if !check(frame) {
        return Err(BusError::Frame("CRC mismatch"));
    }
    if frame[0] != unit.0 {
        return Err(BusError::Frame("unit id does not match the request"));
    }
    Ok(&frame[1..frame.len() - 2])
}

/// The length of the RTU frame answering `request` whose second byte (the function code) is
/// `second`, if it can be an answer at all. Every answer's length follows from the request alone.
#[inline]
fn answer_len(request: &Request<'_>, second: u8) -> Option<usize> {
    let function = request.function();
    if function::is_exception(second) {
        Some(1 + 2 + 2)
    } else if second == function {
        Some(1 + request.response_len() + 2)
    } else {
        None
    }
}

/// Finds the answer to `request` from `unit` in `buf`, trying every offset so that leading
/// garbage, corrupted frames and answers to other requests are skipped.
#[inline]
pub fn scan(unit: UnitId, request: &Request<'_>, buf: &[u8]) -> Scan {
    match registers_at_start(unit, request, buf) {
        Some((len, _)) => Scan::Found { start: 0, len },
        None => scan_every_offset(unit, request, buf),
    }
}

/// If `buf` starts with the normal answer to register read `request` from `unit`: the frame's
/// length and its register bytes. The address, function code and byte count follow from the
/// request and the CRC must match: exactly what [`scan`] accepts at offset 0. Anything else is
/// left to the general scan.
#[inline]
pub fn registers_at_start<'a>(
    unit: UnitId,
    request: &Request<'_>,
    buf: &'a [u8],
) -> Option<(usize, &'a [u8])> {
    let ([function, bytes], pdu_len) = request.register_answer()?;
    let frame = buf.get(..1 + pdu_len + 2)?;
    // Byte by byte: a three-byte array would be stored and reloaded, which stalls the load.
    let head_matches = frame[0] == unit.0 && frame[1] == function && frame[2] == bytes;
    (head_matches && check(frame)).then(|| (frame.len(), &frame[3..frame.len() - 2]))
}

/// [`scan`] the slow way: a candidate frame at every offset.
#[inline]
fn scan_every_offset(unit: UnitId, request: &Request<'_>, buf: &[u8]) -> Scan {
    let mut rejected = None;
    let mut pending = None;
    for start in 0..buf.len() {
        let candidate = &buf[start..];
        if candidate[0] != unit.0 {
            continue;
        }
        let Some(&second) = candidate.get(1) else {
            pending.get_or_insert(start);
            continue;
        };
        let Some(len) = answer_len(request, second) else {
            continue;
        };
        let Some(frame) = candidate.get(..len) else {
            pending.get_or_insert(start);
            continue;
        };
        if !check(frame) {
            rejected = Some("CRC mismatch");
            continue;
        }
        match answers(request, &frame[1..len - 2]) {
            Ok(()) => return Scan::Found { start, len },
            Err(why) => rejected = Some(why),
        }
    }
    Scan::Incomplete {
        discard: pending.unwrap_or(buf.len()),
        rejected,
    }
}

/// RTU framing for the blocking client.
#[derive(Debug, Clone, Copy, Default)]
pub struct RtuFraming;

impl Framing for RtuFraming {
    const MAX_ADU: usize = MAX_ADU;

    #[inline]
    fn encode_request(
        &mut self,
        unit: UnitId,
        request: &Request<'_>,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        encode_request(unit, request, out)
    }

    #[inline]
    fn scan(&self, unit: UnitId, request: &Request<'_>, buf: &[u8]) -> Scan {
        scan(unit, request, buf)
    }

    #[inline]
    fn registers_at_start<'a>(
        &self,
        unit: UnitId,
        request: &Request<'_>,
        buf: &'a [u8],
    ) -> Option<(usize, &'a [u8])> {
        registers_at_start(unit, request, buf)
    }

    #[inline]
    fn pdu<'a>(&self, frame: &'a [u8]) -> &'a [u8] {
        frame.get(1..frame.len().saturating_sub(2)).unwrap_or(&[])
    }
}

/// Parity of a serial line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Parity {
    /// No parity bit.
    None,
    /// Even parity (the Modbus default).
    #[default]
    Even,
    /// Odd parity.
    Odd,
}

/// Stop bits of a serial line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum StopBits {
    /// One stop bit.
    #[default]
    One,
    /// Two stop bits.
    Two,
}

/// The silent intervals of an RTU line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Timing {
    /// Time to send one character.
    pub character: Duration,
    /// Longest silence allowed inside a frame.
    pub t1_5: Duration,
    /// Shortest silence between frames.
    pub t3_5: Duration,
}

impl Timing {
    /// Above this rate the specification fixes t1.5 and t3.5 instead of scaling them.
    pub const FIXED_ABOVE_BAUD: u32 = 19_200;

    /// Timing of a line with 8 data bits at `baud`, with the given parity and stop bits.
    #[inline]
    pub fn new(baud: u32, parity: Parity, stop_bits: StopBits) -> Self {
        let bits =
            1 + 8 + u64::from(parity != Parity::None) + 1 + u64::from(stop_bits == StopBits::Two);
        let character = Duration::from_nanos(bits * 1_000_000_000 / u64::from(baud.max(1)));
        if baud > Self::FIXED_ABOVE_BAUD {
            Self {
                character,
                t1_5: Duration::from_micros(750),
                t3_5: Duration::from_micros(1750),
            }
        } else {
            Self {
                character,
                t1_5: character * 3 / 2,
                t3_5: character * 7 / 2,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modbus::damage::damage;
    use crate::modbus::pdu::{encode_exception, encode_registers_response};
    use proptest::prelude::*;
    use std::vec::Vec;

    const UNIT: UnitId = UnitId(1);

    fn frame(unit: UnitId, request: &Request<'_>) -> Vec<u8> {
        let mut out = [0u8; MAX_ADU];
        let len = encode_request(unit, request, &mut out).unwrap();
        out[..len].to_vec()
    }

    fn reply(unit: u8, pdu: &[u8]) -> Vec<u8> {
        let mut out = [0u8; MAX_ADU];
        out[0] = unit;
        out[1..=pdu.len()].copy_from_slice(pdu);
        let len = seal(&mut out, 1 + pdu.len()).unwrap();
        out[..len].to_vec()
    }

    fn registers_reply(unit: u8, function: u8, values: &[u16]) -> Vec<u8> {
        let mut pdu = [0u8; MAX_PDU];
        let len = encode_registers_response(function, values, &mut pdu).unwrap();
        reply(unit, &pdu[..len])
    }

    /// The request frames of the Lafert Modbus manual (§1.2, §1.3), CRCs computed independently.
    #[test]
    fn lafert_manual_frames() {
        let write = |address, value| Request::WriteSingleRegister { address, value };
        let cases: [(Request<'_>, [u8; 8]); 9] = [
            (
                write(0x0028, 2),
                [0x01, 0x06, 0x00, 0x28, 0x00, 0x02, 0x88, 0x03],
            ),
            (
                write(0x0000, 1),
                [0x01, 0x06, 0x00, 0x00, 0x00, 0x01, 0x48, 0x0A],
            ),
            (
                write(0xA5A5, 1),
                [0x01, 0x06, 0xA5, 0xA5, 0x00, 0x01, 0x7A, 0xE5],
            ),
            (
                write(0x0035, 0x60),
                [0x01, 0x06, 0x00, 0x35, 0x00, 0x60, 0x99, 0xEC],
            ),
            (
                write(0x002B, 1),
                [0x01, 0x06, 0x00, 0x2B, 0x00, 0x01, 0x38, 0x02],
            ),
            (
                Request::ReadInputRegisters {
                    start: 0x0060,
                    count: 1,
                },
                [0x01, 0x04, 0x00, 0x60, 0x00, 0x01, 0x31, 0xD4],
            ),
            // The manual prints "00 2B 00 17" here; its text means 0x0060..=0x0070, 17 = 0x11.
            (
                Request::ReadInputRegisters {
                    start: 0x0060,
                    count: 17,
                },
                [0x01, 0x04, 0x00, 0x60, 0x00, 0x11, 0x30, 0x18],
            ),
            (
                Request::ReadHoldingRegisters {
                    start: 0x002B,
                    count: 1,
                },
                [0x01, 0x03, 0x00, 0x2B, 0x00, 0x01, 0xF4, 0x02],
            ),
            (
                Request::ReadHoldingRegisters {
                    start: 0x003C,
                    count: 6,
                },
                [0x01, 0x03, 0x00, 0x3C, 0x00, 0x06, 0x05, 0xC4],
            ),
        ];
        for (request, expected) in cases {
            assert_eq!(frame(UNIT, &request), expected, "{request:?}");
        }
    }

    #[test]
    fn scan_skips_garbage_corruption_and_other_units() {
        let request = Request::ReadHoldingRegisters {
            start: 0x3C,
            count: 2,
        };
        let good = registers_reply(1, 3, &[0x1234, 0x5678]);
        let mut corrupt = good.clone();
        corrupt[4] ^= 0x40;
        let other_unit = registers_reply(2, 3, &[9, 9]);
        let mut buf = std::vec![0x01, 0x03, 0xFF, 0x00];
        buf.extend_from_slice(&corrupt);
        buf.extend_from_slice(&other_unit);
        let at = buf.len();
        buf.extend_from_slice(&good);
        assert_eq!(
            scan(UNIT, &request, &buf),
            Scan::Found {
                start: at,
                len: good.len()
            }
        );
        let frame = &buf[at..at + good.len()];
        assert_eq!(open_frame(UNIT, frame).unwrap(), &good[1..good.len() - 2]);
        assert_eq!(
            open_frame(UnitId(2), frame),
            Err(BusError::Frame("unit id does not match the request"))
        );
    }

    #[test]
    fn scan_waits_for_a_truncated_frame_and_reports_a_bad_crc() {
        let request = Request::ReadInputRegisters {
            start: 0x60,
            count: 1,
        };
        let good = registers_reply(1, 4, &[7]);
        assert_eq!(
            scan(UNIT, &request, &good[..5]),
            Scan::Incomplete {
                discard: 0,
                rejected: None
            }
        );
        let mut corrupt = good.clone();
        corrupt[6] ^= 1;
        assert_eq!(
            scan(UNIT, &request, &corrupt),
            Scan::Incomplete {
                discard: corrupt.len(),
                rejected: Some("CRC mismatch")
            }
        );
        // A stale answer to another read (other count) is not taken for this one.
        let stale = registers_reply(1, 4, &[7, 8]);
        assert!(matches!(
            scan(UNIT, &request, &stale),
            Scan::Incomplete { .. }
        ));
    }

    #[test]
    fn exception_answers_are_found() {
        let request = Request::ReadHoldingRegisters {
            start: 0x9999,
            count: 1,
        };
        let mut pdu = [0u8; 2];
        encode_exception(3, 2, &mut pdu).unwrap();
        let answer = reply(1, &pdu);
        assert_eq!(answer, [0x01, 0x83, 0x02, 0xC0, 0xF1]);
        assert_eq!(
            scan(UNIT, &request, &answer),
            Scan::Found { start: 0, len: 5 }
        );
    }

    #[test]
    fn silent_intervals_follow_the_baud_rate() {
        let t = Timing::new(9600, Parity::Even, StopBits::One);
        // 11 bits at 9600 Bd: 1145.8 µs per character.
        assert_eq!(t.character.as_nanos(), 1_145_833);
        assert_eq!(t.t1_5.as_nanos(), 1_718_749);
        assert_eq!(t.t3_5.as_nanos(), 4_010_415);
        let t = Timing::new(19_200, Parity::None, StopBits::One);
        assert_eq!(t.character.as_nanos(), 520_833);
        assert_eq!(t.t3_5.as_nanos(), 1_822_915);
        for baud in [38_400, 115_200] {
            let t = Timing::new(baud, Parity::Even, StopBits::Two);
            assert_eq!(t.t1_5, Duration::from_micros(750));
            assert_eq!(t.t3_5, Duration::from_micros(1750));
        }
        assert!(Timing::new(0, Parity::None, StopBits::One).t3_5 > Duration::ZERO);
    }

    proptest! {
        #[test]
        fn scan_never_panics_and_only_finds_valid_frames(
            bytes in proptest::collection::vec(any::<u8>(), 0..600),
            count in 1u16..=125,
        ) {
            let request = Request::ReadHoldingRegisters { start: 0, count };
            match scan(UNIT, &request, &bytes) {
                Scan::Found { start, len } => {
                    let pdu = open_frame(UNIT, &bytes[start..start + len]).unwrap();
                    prop_assert!(answers(&request, pdu).is_ok());
                }
                Scan::Incomplete { discard, .. } => prop_assert!(discard <= bytes.len()),
            }
            let _ = open_frame(UNIT, &bytes);
            let _ = registers_at_start(UNIT, &request, &bytes);
        }

        #[test]
        fn the_fast_path_accepts_exactly_what_the_general_scan_accepts(
            values in proptest::collection::vec(any::<u16>(), 1..=125),
            other_count in proptest::option::of(1u16..=125),
            (unit, function) in (1u8..=2, prop::sample::select(&[3u8, 4, 0x83][..])),
            flip in proptest::option::of((any::<prop::sample::Index>(), 1u8..)),
            cut in proptest::option::of(any::<prop::sample::Index>()),
            tail in proptest::collection::vec(any::<u8>(), 0..12),
        ) {
            let count = other_count.unwrap_or(values.len() as u16);
            let request = Request::ReadHoldingRegisters { start: 0, count };
            let mut buf = if function == 0x83 {
                reply(unit, &[0x83, 2])
            } else {
                registers_reply(unit, function, &values)
            };
            damage(&mut buf, flip, cut);
            buf.extend_from_slice(&tail);
            let intact = flip.is_none() && cut.is_none() && other_count.is_none();
            if intact && function == 3 && unit == 1 {
                prop_assert!(registers_at_start(UNIT, &request, &buf).is_some());
            }
            let general = scan_every_offset(UNIT, &request, &buf);
            prop_assert_eq!(scan(UNIT, &request, &buf), general);
            match registers_at_start(UNIT, &request, &buf) {
                Some((len, data)) => {
                    prop_assert_eq!(general, Scan::Found { start: 0, len });
                    prop_assert_eq!(data, &buf[3..len - 2]);
                }
                // Only exceptions are left to the general scan.
                None => {
                    let found_at_start = matches!(general, Scan::Found { start: 0, .. });
                    prop_assert!(!found_at_start || buf[1] == 0x83, "fast path missed an answer");
                }
            }
        }

        #[test]
        fn answers_are_found_behind_any_garbage(
            garbage in proptest::collection::vec(any::<u8>(), 0..300),
            values in proptest::collection::vec(any::<u16>(), 1..=125),
        ) {
            let request = Request::ReadInputRegisters { start: 0, count: values.len() as u16 };
            let good = registers_reply(1, 4, &values);
            let mut buf = garbage.clone();
            buf.extend_from_slice(&good);
            let Scan::Found { start, len } = scan(UNIT, &request, &buf) else {
                return Err(TestCaseError::fail("answer not found"));
            };
            // A CRC-valid frame hidden in the garbage is possible but must still decode validly.
            let pdu = open_frame(UNIT, &buf[start..start + len]).unwrap();
            prop_assert!(answers(&request, pdu).is_ok());
            if start == garbage.len() {
                prop_assert_eq!(&buf[start..], &good[..]);
            }
        }
    }
}

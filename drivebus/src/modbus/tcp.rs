//! Modbus TCP: the MBAP header (transaction id, protocol 0, length, unit id) around a PDU.

use crate::error::BusError;

use super::address::UnitId;
use super::framing::{answers, Framing, Scan};
use super::pdu::{Request, MAX_PDU};

/// Length of the MBAP header.
pub const HEADER_LEN: usize = 7;
/// Largest TCP ADU: header and 253-byte PDU.
pub const MAX_ADU: usize = HEADER_LEN + MAX_PDU;

/// A decoded MBAP header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Header {
    /// Transaction id, echoed by the server.
    pub transaction: u16,
    /// Unit id.
    pub unit: UnitId,
    /// Length of the PDU that follows.
    pub pdu_len: usize,
}

impl Header {
    /// Parses the first [`HEADER_LEN`] bytes of `bytes`. Protocol ids other than 0 and lengths no
    /// PDU can have are rejected: after either the stream is out of step.
    #[inline]
    pub fn parse(bytes: &[u8]) -> Result<Self, BusError> {
        parse_header(bytes).map_err(BusError::Frame)
    }

    /// Writes the header for a PDU of `pdu_len` bytes into `out`.
    #[inline]
    pub fn write(&self, out: &mut [u8]) -> Result<(), BusError> {
        if self.pdu_len > MAX_PDU {
            return Err(BusError::Unsupported("PDU longer than 253 bytes"));
        }
        let head = out.get_mut(..HEADER_LEN).ok_or(BusError::Unsupported(
            "output buffer too small for the header",
        ))?;
        head[..2].copy_from_slice(&self.transaction.to_be_bytes());
        head[2..4].copy_from_slice(&[0, 0]);
        head[4..6].copy_from_slice(&(self.pdu_len as u16 + 1).to_be_bytes());
        head[6] = self.unit.0;
        Ok(())
    }
}

#[inline]
fn parse_header(bytes: &[u8]) -> Result<Header, &'static str> {
    let head = bytes.get(..HEADER_LEN).ok_or("MBAP header too short")?;
    if head[2..4] != [0, 0] {
        return Err("MBAP protocol id is not 0");
    }
    let length = u16::from_be_bytes([head[4], head[5]]) as usize;
    if !(2..=1 + MAX_PDU).contains(&length) {
        return Err("MBAP length out of range");
    }
    Ok(Header {
        transaction: u16::from_be_bytes([head[0], head[1]]),
        unit: UnitId(head[6]),
        pdu_len: length - 1,
    })
}

/// Encodes `request` as an MBAP ADU into `out`; returns its length.
#[inline]
pub fn encode_request(
    transaction: u16,
    unit: UnitId,
    request: &Request<'_>,
    out: &mut [u8],
) -> Result<usize, BusError> {
    let body = out.get_mut(HEADER_LEN..).ok_or(BusError::Unsupported(
        "output buffer too small for the request",
    ))?;
    let pdu_len = request.encode(body)?;
    Header {
        transaction,
        unit,
        pdu_len,
    }
    .write(out)?;
    Ok(HEADER_LEN + pdu_len)
}

/// Checks an MBAP frame's header against the request's transaction and unit; returns the PDU.
#[inline]
pub fn open_frame(transaction: u16, unit: UnitId, frame: &[u8]) -> Result<&[u8], BusError> {
    let header = Header::parse(frame)?;
    if frame.len() != HEADER_LEN + header.pdu_len {
        return Err(BusError::Frame("MBAP length does not match the frame"));
    }
    if header.transaction != transaction {
        return Err(BusError::Frame("transaction id does not match the request"));
    }
    if header.unit != unit {
        return Err(BusError::Frame("unit id does not match the request"));
    }
    Ok(&frame[HEADER_LEN..])
}

/// What the bytes at a frame boundary hold, as far as the current request is concerned.
enum Verdict {
    /// The answer, `len` bytes long.
    Answer(usize),
    /// A complete frame of `len` bytes that does not answer the request.
    Other(usize, &'static str),
    /// The start of a frame that has not arrived completely.
    Partial,
    /// A header no frame can have: the stream is out of step.
    OutOfStep(&'static str),
}

/// Judges the frame at the start of `bytes`.
#[inline]
fn judge(transaction: u16, unit: UnitId, request: &Request<'_>, bytes: &[u8]) -> Verdict {
    if bytes.len() < HEADER_LEN {
        return Verdict::Partial;
    }
    let header = match parse_header(bytes) {
        Ok(header) => header,
        Err(why) => return Verdict::OutOfStep(why),
    };
    let len = HEADER_LEN + header.pdu_len;
    let Some(frame) = bytes.get(..len) else {
        return Verdict::Partial;
    };
    let verdict = if header.transaction != transaction {
        Err("transaction id does not match the request")
    } else if header.unit != unit {
        Err("unit id does not match the request")
    } else {
        answers(request, &frame[HEADER_LEN..])
    };
    match verdict {
        Ok(()) => Verdict::Answer(len),
        Err(why) => Verdict::Other(len, why),
    }
}

/// Finds the answer to transaction `transaction` in `buf`, which starts at a frame boundary.
/// Frames of other transactions (late answers to earlier requests) are skipped; a header that
/// cannot be valid means the stream lost step, and everything buffered is discarded.
#[inline]
pub fn scan(transaction: u16, unit: UnitId, request: &Request<'_>, buf: &[u8]) -> Scan {
    match registers_at_start(transaction, unit, request, buf) {
        Some((len, _)) => Scan::Found { start: 0, len },
        None => scan_past_others(transaction, unit, request, buf),
    }
}

/// If `buf` starts with the normal answer to register read `request`: the frame's length and its
/// register bytes. Every byte up to the data follows from the request, so one comparison replaces
/// the general scan's field-by-field checks, and accepts exactly the frames they accept at the
/// start. Anything else (exceptions, other requests, stale or malformed frames) is left to them.
#[inline]
pub fn registers_at_start<'a>(
    transaction: u16,
    unit: UnitId,
    request: &Request<'_>,
    buf: &'a [u8],
) -> Option<(usize, &'a [u8])> {
    let ([function, bytes], pdu_len) = request.register_answer()?;
    let frame = buf.get(..HEADER_LEN + pdu_len)?;
    let (head, rest) = frame.split_first_chunk::<8>()?;
    // Transaction, protocol 0, MBAP length, unit, function code: built in a register, because
    // bytes stored one by one and reloaded as a word stall the load.
    let expected = u64::from(transaction) << 48
        | (pdu_len as u64 + 1) << 16
        | u64::from(unit.0) << 8
        | u64::from(function);
    match rest.split_first() {
        Some((&count, data)) if u64::from_be_bytes(*head) == expected && count == bytes => {
            Some((frame.len(), data))
        }
        _ => None,
    }
}

/// [`scan`] from the first frame on, skipping the frames that do not answer the request.
#[inline(never)]
fn scan_past_others(transaction: u16, unit: UnitId, request: &Request<'_>, buf: &[u8]) -> Scan {
    let mut start = 0;
    let mut rejected = None;
    loop {
        match judge(transaction, unit, request, &buf[start..]) {
            Verdict::Answer(len) => return Scan::Found { start, len },
            Verdict::Other(len, why) => {
                rejected = Some(why);
                start += len;
            }
            Verdict::Partial => {
                return Scan::Incomplete {
                    discard: start,
                    rejected,
                }
            }
            Verdict::OutOfStep(why) => {
                return Scan::Incomplete {
                    discard: buf.len(),
                    rejected: Some(why),
                }
            }
        }
    }
}

/// MBAP framing for the blocking client: numbers transactions and only accepts the current one.
#[derive(Debug, Clone, Copy, Default)]
pub struct TcpFraming {
    transaction: u16,
}

impl TcpFraming {
    /// Framing whose first request has transaction id `first`.
    #[inline]
    pub fn new(first: u16) -> Self {
        Self {
            transaction: first.wrapping_sub(1),
        }
    }
    /// The transaction id of the request last encoded.
    #[inline]
    pub fn transaction(&self) -> u16 {
        self.transaction
    }
}

impl Framing for TcpFraming {
    const MAX_ADU: usize = MAX_ADU;
    const TAGGED_ANSWERS: bool = true;

    #[inline]
    fn encode_request(
        &mut self,
        unit: UnitId,
        request: &Request<'_>,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        self.transaction = self.transaction.wrapping_add(1);
        encode_request(self.transaction, unit, request, out)
    }

    #[inline]
    fn scan(&self, unit: UnitId, request: &Request<'_>, buf: &[u8]) -> Scan {
        scan(self.transaction, unit, request, buf)
    }

    #[inline]
    fn registers_at_start<'a>(
        &self,
        unit: UnitId,
        request: &Request<'_>,
        buf: &'a [u8],
    ) -> Option<(usize, &'a [u8])> {
        registers_at_start(self.transaction, unit, request, buf)
    }

    #[inline]
    fn pdu<'a>(&self, frame: &'a [u8]) -> &'a [u8] {
        frame.get(HEADER_LEN..).unwrap_or(&[])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modbus::damage::damage;
    use crate::modbus::pdu::encode_registers_response;
    use proptest::prelude::*;
    use std::vec::Vec;

    const UNIT: UnitId = UnitId(1);

    fn answer(transaction: u16, unit: u8, values: &[u16]) -> Vec<u8> {
        let mut out = [0u8; MAX_ADU];
        let len = encode_registers_response(3, values, &mut out[HEADER_LEN..]).unwrap();
        Header {
            transaction,
            unit: UnitId(unit),
            pdu_len: len,
        }
        .write(&mut out)
        .unwrap();
        out[..HEADER_LEN + len].to_vec()
    }

    #[test]
    fn encodes_mbap() {
        let mut out = [0u8; MAX_ADU];
        let request = Request::ReadHoldingRegisters {
            start: 0x3C,
            count: 6,
        };
        let len = encode_request(0x1234, UNIT, &request, &mut out).unwrap();
        assert_eq!(out[..len], [0x12, 0x34, 0, 0, 0, 6, 1, 3, 0, 0x3C, 0, 6]);
    }

    #[test]
    fn skips_stale_transactions_and_other_units() {
        let request = Request::ReadHoldingRegisters { start: 0, count: 1 };
        let mut buf = answer(6, 1, &[1]);
        buf.extend(answer(7, 2, &[2]));
        let at = buf.len();
        buf.extend(answer(7, 1, &[3]));
        assert_eq!(
            scan(7, UNIT, &request, &buf),
            Scan::Found { start: at, len: 11 }
        );
        assert_eq!(
            scan(7, UNIT, &request, &buf[..at]),
            Scan::Incomplete {
                discard: at,
                rejected: Some("unit id does not match the request")
            }
        );
        assert_eq!(
            open_frame(8, UNIT, &buf[at..]),
            Err(BusError::Frame("transaction id does not match the request"))
        );
        assert_eq!(open_frame(7, UNIT, &buf[at..]).unwrap(), [3, 2, 0, 3]);
    }

    #[test]
    fn a_header_out_of_step_discards_everything() {
        let request = Request::ReadHoldingRegisters { start: 0, count: 1 };
        let mut buf = answer(7, 1, &[3]);
        buf[2] = 1;
        assert_eq!(
            scan(7, UNIT, &request, &buf),
            Scan::Incomplete {
                discard: buf.len(),
                rejected: Some("MBAP protocol id is not 0")
            }
        );
        assert_eq!(
            scan(7, UNIT, &request, &buf[..9]),
            Scan::Incomplete {
                discard: 9,
                rejected: Some("MBAP protocol id is not 0")
            }
        );
        let good = answer(7, 1, &[3]);
        assert_eq!(
            scan(7, UNIT, &request, &good[..9]),
            Scan::Incomplete {
                discard: 0,
                rejected: None
            }
        );
    }

    proptest! {
        #[test]
        fn scan_and_parse_never_panic(
            bytes in proptest::collection::vec(any::<u8>(), 0..600),
            transaction in any::<u16>(),
        ) {
            let request = Request::ReadInputRegisters { start: 0, count: 3 };
            if let Scan::Found { start, len } = scan(transaction, UNIT, &request, &bytes) {
                let pdu = open_frame(transaction, UNIT, &bytes[start..start + len]).unwrap();
                prop_assert!(answers(&request, pdu).is_ok());
            }
            let _ = Header::parse(&bytes);
            let _ = registers_at_start(transaction, UNIT, &request, &bytes);
        }

        #[test]
        fn the_fast_path_accepts_exactly_what_the_general_scan_accepts(
            values in proptest::collection::vec(any::<u16>(), 1..=125),
            other_count in proptest::option::of(1u16..=125),
            (transaction, other_transaction, unit) in (any::<u16>(), any::<bool>(), 1u8..=2),
            exception in any::<bool>(),
            flip in proptest::option::of((any::<prop::sample::Index>(), 1u8..)),
            cut in proptest::option::of(any::<prop::sample::Index>()),
            tail in proptest::collection::vec(any::<u8>(), 0..12),
        ) {
            let count = other_count.unwrap_or(values.len() as u16);
            let request = Request::ReadHoldingRegisters { start: 0, count };
            let sent = transaction.wrapping_add(u16::from(other_transaction));
            let mut buf = answer(sent, unit, &values);
            if exception {
                buf.truncate(HEADER_LEN + 2);
                buf[5] = 3;
                buf[HEADER_LEN..].copy_from_slice(&[0x83, 2]);
            }
            damage(&mut buf, flip, cut);
            buf.extend_from_slice(&tail);
            let intact = flip.is_none() && cut.is_none() && other_count.is_none();
            if intact && !exception && !other_transaction && unit == 1 {
                prop_assert!(registers_at_start(transaction, UNIT, &request, &buf).is_some());
            }
            let general = scan_past_others(transaction, UNIT, &request, &buf);
            prop_assert_eq!(scan(transaction, UNIT, &request, &buf), general);
            match registers_at_start(transaction, UNIT, &request, &buf) {
                Some((len, data)) => {
                    prop_assert_eq!(general, Scan::Found { start: 0, len });
                    prop_assert_eq!(data, &buf[HEADER_LEN + 2..len]);
                }
                // Only exceptions are left to the general scan.
                None => {
                    let found_at_start = matches!(general, Scan::Found { start: 0, .. });
                    prop_assert!(!found_at_start || buf[HEADER_LEN] & 0x80 != 0, "fast path missed an answer");
                }
            }
        }

        #[test]
        fn encode_then_open_round_trips(transaction in any::<u16>(), unit in any::<u8>(), start in 0u16..0xFF00, count in 1u16..=125) {
            let request = Request::ReadInputRegisters { start, count };
            let mut out = [0u8; MAX_ADU];
            let len = encode_request(transaction, UnitId(unit), &request, &mut out).unwrap();
            prop_assert_eq!(open_frame(transaction, UnitId(unit), &out[..len]).unwrap(), &out[HEADER_LEN..len]);
        }
    }
}

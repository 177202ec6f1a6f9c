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

/// Finds the answer to transaction `transaction` in `buf`, which starts at a frame boundary.
/// Frames of other transactions (late answers to earlier requests) are skipped; a header that
/// cannot be valid means the stream lost step, and everything buffered is discarded.
#[inline]
pub fn scan(transaction: u16, unit: UnitId, request: &Request<'_>, buf: &[u8]) -> Scan {
    let mut start = 0;
    let mut rejected = None;
    while let Some(rest) = buf.get(start..).filter(|rest| rest.len() >= HEADER_LEN) {
        let header = match parse_header(rest) {
            Ok(header) => header,
            Err(why) => {
                return Scan::Incomplete {
                    discard: buf.len(),
                    rejected: Some(why),
                }
            }
        };
        let len = HEADER_LEN + header.pdu_len;
        let Some(frame) = rest.get(..len) else {
            break;
        };
        let verdict = if header.transaction != transaction {
            Err("transaction id does not match the request")
        } else if header.unit != unit {
            Err("unit id does not match the request")
        } else {
            answers(request, &frame[HEADER_LEN..])
        };
        match verdict {
            Ok(()) => return Scan::Found { start, len },
            Err(why) => rejected = Some(why),
        }
        start += len;
    }
    Scan::Incomplete {
        discard: start,
        rejected,
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
    fn pdu<'a>(&self, frame: &'a [u8]) -> &'a [u8] {
        frame.get(HEADER_LEN..).unwrap_or(&[])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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

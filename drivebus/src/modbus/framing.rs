//! What RTU and TCP framing have in common, so one blocking client drives both.

use crate::error::BusError;

use super::address::UnitId;
use super::pdu::{decode_registers, Registers, Request};

/// Outcome of looking for the answer to a request in received bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scan {
    /// `buf[start..start + len]` is a frame answering the request (a normal or an exception
    /// response); everything else in the buffer is garbage or stale.
    Found {
        /// Offset of the frame.
        start: usize,
        /// Length of the frame.
        len: usize,
    },
    /// No answer yet.
    Incomplete {
        /// Leading bytes that can never be part of the answer and may be dropped.
        discard: usize,
        /// Why the last complete candidate frame was rejected, if one was.
        rejected: Option<&'static str>,
    },
}

/// A Modbus framing (ADU format): RTU or MBAP. A copy remembers the request last encoded, which
/// is how a client keeps track of several requests in flight.
pub trait Framing: Copy {
    /// Largest ADU of this framing.
    const MAX_ADU: usize;
    /// Whether an answer names the request it answers (MBAP's transaction id), so several
    /// requests may await their answers at once. RTU answers only by order: one at a time.
    const TAGGED_ANSWERS: bool = false;

    /// Encodes `request` to `unit` into `out`; returns the ADU length.
    fn encode_request(
        &mut self,
        unit: UnitId,
        request: &Request<'_>,
        out: &mut [u8],
    ) -> Result<usize, BusError>;

    /// Looks for the answer to the request last encoded in `buf`, skipping garbage, frames with a
    /// bad checksum and frames that answer something else.
    fn scan(&self, unit: UnitId, request: &Request<'_>, buf: &[u8]) -> Scan;

    /// The PDU inside a frame that [`scan`](Self::scan) found.
    fn pdu<'a>(&self, frame: &'a [u8]) -> &'a [u8];

    /// If `buf` starts with the normal answer to register read `request`: the frame's length and
    /// its register bytes, found with the fewest checks possible. Must accept only frames
    /// [`scan`](Self::scan) finds at offset 0; `None` (the default) leaves everything to it.
    #[inline]
    fn registers_at_start<'a>(
        &self,
        unit: UnitId,
        request: &Request<'_>,
        buf: &'a [u8],
    ) -> Option<(usize, &'a [u8])> {
        let _ = (unit, request, buf);
        None
    }
}

/// Looks for the answer to register read `request` in `buf` like [`Framing::scan`] and decodes
/// it into `out` (one slot per requested register) like [`decode_registers`].
///
/// `Ok(Scan::Found)`: the answer is at the place given and its registers are in `out`.
/// `Err`: the answer was found but is an exception (or `out` has the wrong length).
/// `Ok(Scan::Incomplete)`: no answer yet. In the usual case — the buffer holds just the answer —
/// the frame is checked once and decoded in the same pass.
#[inline]
pub fn scan_registers<F: Framing>(
    framing: &F,
    unit: UnitId,
    request: &Request<'_>,
    buf: &[u8],
    out: &mut [u16],
) -> Result<Scan, BusError> {
    match framing.registers_at_start(unit, request, buf) {
        Some((len, bytes)) => {
            Registers::new(bytes).copy_to(out)?;
            Ok(Scan::Found { start: 0, len })
        }
        // By value into a call out of line: the fast path keeps the framing and the request in
        // registers instead of laying them out in memory for a call it rarely makes.
        None => scan_then_decode(*framing, unit, *request, buf, out),
    }
}

/// [`scan_registers`] the general way: everything but a clean answer at the start of the buffer.
#[inline(never)]
fn scan_then_decode<F: Framing>(
    framing: F,
    unit: UnitId,
    request: Request<'_>,
    buf: &[u8],
    out: &mut [u16],
) -> Result<Scan, BusError> {
    let scan = framing.scan(unit, &request, buf);
    if let Scan::Found { start, len } = scan {
        decode_registers(&request, framing.pdu(&buf[start..start + len]), out)?;
    }
    Ok(scan)
}

/// Whether a PDU is an acceptable answer: a matching normal response or an exception.
#[inline]
pub(crate) fn answers(request: &Request<'_>, pdu: &[u8]) -> Result<(), &'static str> {
    match super::pdu::decode_response(request, pdu) {
        Ok(_) | Err(BusError::ModbusException { .. }) => Ok(()),
        Err(BusError::Frame(why)) => Err(why),
        Err(_) => Err("response does not match the request"),
    }
}

#[cfg(all(test, feature = "modbus-core"))]
mod tests {
    use super::*;
    use crate::modbus::damage::damage;
    use crate::modbus::pdu::{encode_exception, encode_registers_response, MAX_PDU};
    use crate::modbus::rtu::{self, RtuFraming};
    use crate::modbus::tcp::{self, Header, TcpFraming};
    use proptest::prelude::*;
    use std::vec::Vec;

    const UNIT: UnitId = UnitId(1);
    const READ: Request<'static> = Request::ReadHoldingRegisters { start: 0, count: 3 };

    /// `pdu` from `unit` as an MBAP frame of `transaction`, or as an RTU frame.
    fn wrap(transaction: Option<u16>, unit: u8, pdu: &[u8]) -> Vec<u8> {
        let mut out = std::vec![0u8; tcp::MAX_ADU];
        let len = match transaction {
            Some(transaction) => {
                let header = Header {
                    transaction,
                    unit: UnitId(unit),
                    pdu_len: pdu.len(),
                };
                header.write(&mut out).unwrap();
                out[tcp::HEADER_LEN..][..pdu.len()].copy_from_slice(pdu);
                tcp::HEADER_LEN + pdu.len()
            }
            None => {
                out[0] = unit;
                out[1..=pdu.len()].copy_from_slice(pdu);
                rtu::seal(&mut out, 1 + pdu.len()).unwrap()
            }
        };
        out.truncate(len);
        out
    }

    fn registers_pdu(values: &[u16]) -> Vec<u8> {
        let mut pdu = [0u8; MAX_PDU];
        let len = encode_registers_response(3, values, &mut pdu).unwrap();
        pdu[..len].to_vec()
    }

    /// A TCP framing whose current transaction is 7.
    fn tcp_framing() -> TcpFraming {
        let mut framing = TcpFraming::new(7);
        framing
            .encode_request(UNIT, &READ, &mut [0u8; tcp::MAX_ADU])
            .unwrap();
        framing
    }

    /// `scan_registers` must give what scanning and then decoding gives, in `out` too.
    fn agrees<F: Framing>(
        framing: &F,
        request: &Request<'_>,
        buf: &[u8],
        slots: usize,
    ) -> Result<(), TestCaseError> {
        let (mut fast, mut general) = (std::vec![0u16; slots], std::vec![0u16; slots]);
        let got = scan_registers(framing, UNIT, request, buf, &mut fast);
        let expected = scan_then_decode(*framing, UNIT, *request, buf, &mut general);
        prop_assert_eq!(got, expected);
        prop_assert_eq!(fast, general);
        Ok(())
    }

    fn scans_and_decodes<F: Framing>(framing: F, transaction: Option<u16>) {
        let answer = wrap(transaction, 1, &registers_pdu(&[1, 2, 3]));
        let mut out = [0u16; 3];
        let found = Scan::Found {
            start: 0,
            len: answer.len(),
        };
        assert_eq!(
            scan_registers(&framing, UNIT, &READ, &answer, &mut out),
            Ok(found)
        );
        assert_eq!(out, [1, 2, 3]);
        // Behind a stale answer from another unit: found the general way.
        let mut buf = wrap(transaction, 2, &registers_pdu(&[9, 9, 9]));
        let start = buf.len();
        buf.extend(wrap(transaction, 1, &registers_pdu(&[4, 5, 6])));
        let len = buf.len() - start;
        assert_eq!(
            scan_registers(&framing, UNIT, &READ, &buf, &mut out),
            Ok(Scan::Found { start, len })
        );
        assert_eq!(out, [4, 5, 6]);
        let mut pdu = [0u8; 2];
        encode_exception(3, 2, &mut pdu).unwrap();
        assert_eq!(
            scan_registers(&framing, UNIT, &READ, &wrap(transaction, 1, &pdu), &mut out),
            Err(BusError::ModbusException {
                function: 3,
                code: crate::modbus::ExceptionCode::IllegalDataAddress
            })
        );
        assert!(matches!(
            scan_registers(&framing, UNIT, &READ, &answer[..answer.len() - 1], &mut out),
            Ok(Scan::Incomplete { .. })
        ));
        assert_eq!(
            scan_registers(&framing, UNIT, &READ, &answer, &mut [0u16; 2]),
            Err(BusError::Frame("register count does not match the request"))
        );
        assert_eq!(out, [4, 5, 6], "only accepted answers are written");
    }

    #[test]
    fn scan_registers_decodes_answers_and_reports_exceptions() {
        scans_and_decodes(RtuFraming, None);
        scans_and_decodes(tcp_framing(), Some(7));
    }

    proptest! {
        #[test]
        fn scan_registers_never_panics_and_agrees_on_arbitrary_bytes(
            bytes in proptest::collection::vec(any::<u8>(), 0..600),
            count in 1u16..=125,
            slots in 0usize..130,
        ) {
            let request = Request::ReadInputRegisters { start: 0, count };
            agrees(&RtuFraming, &request, &bytes, slots)?;
            agrees(&tcp_framing(), &request, &bytes, slots)?;
        }

        #[test]
        fn scan_registers_agrees_on_damaged_answers(
            values in proptest::collection::vec(any::<u16>(), 1..=125),
            other_count in proptest::option::of(1u16..=125),
            tcp in any::<bool>(),
            garbage in proptest::collection::vec(any::<u8>(), 0..4),
            flip in proptest::option::of((any::<prop::sample::Index>(), 1u8..)),
            cut in proptest::option::of(any::<prop::sample::Index>()),
        ) {
            let count = other_count.unwrap_or(values.len() as u16);
            let request = Request::ReadHoldingRegisters { start: 0, count };
            let clean = garbage.is_empty();
            let mut buf = garbage;
            buf.extend(wrap(tcp.then_some(7), 1, &registers_pdu(&values)));
            damage(&mut buf, flip, cut);
            let mut out = std::vec![0u16; values.len()];
            let found = if tcp {
                agrees(&tcp_framing(), &request, &buf, values.len())?;
                scan_registers(&tcp_framing(), UNIT, &request, &buf, &mut out)
            } else {
                agrees(&RtuFraming, &request, &buf, values.len())?;
                scan_registers(&RtuFraming, UNIT, &request, &buf, &mut out)
            };
            if clean && flip.is_none() && cut.is_none() && other_count.is_none() {
                let len = buf.len();
                prop_assert_eq!(found, Ok(Scan::Found { start: 0, len }));
                prop_assert_eq!(out, values);
            }
        }
    }
}

//! What a Modbus response scanner (RTU or MBAP) must hold for any received bytes.

use drivebus::modbus::framing::{scan_registers, Framing, Scan};
use drivebus::modbus::pdu::{decode_registers, decode_response, Request};
use drivebus::modbus::UnitId;
use drivebus::BusError;

/// Checks `framing`'s scan of `buf` for the answer to `request` from `unit`:
///
/// * a frame it finds lies inside the buffer, `open` (the framing's own frame check) accepts
///   it, and its PDU decodes as the answer to `request` (a normal response or an exception);
/// * the register fast path agrees with the general scan and decodes the same registers;
/// * bytes a scan of the first `split` bytes calls discardable are never part of the answer the
///   whole buffer holds, and scanning without them finds the same frame: what a streaming client
///   relies on when it drops them.
pub fn check<F: Framing>(
    framing: &F,
    unit: UnitId,
    request: &Request<'_>,
    buf: &[u8],
    split: usize,
    open: impl Fn(&[u8]) -> Result<&[u8], BusError>,
) {
    let whole = framing.scan(unit, request, buf);
    if let Scan::Found { start, len } = whole {
        let frame = buf
            .get(start..start + len)
            .unwrap_or_else(|| panic!("found frame {start}+{len} outside {} bytes", buf.len()));
        let pdu = open(frame).unwrap_or_else(|e| panic!("found frame refused by its check: {e}"));
        assert_eq!(
            pdu,
            framing.pdu(frame),
            "framing's PDU differs from the frame check's"
        );
        match decode_response(request, pdu) {
            Ok(_) | Err(BusError::ModbusException { .. }) => {}
            Err(e) => panic!("found frame does not answer the request: {e}"),
        }
    }
    check_registers(framing, unit, request, buf, whole);
    check_discard(framing, unit, request, buf, split.min(buf.len()), whole);
}

/// `scan_registers` finds what `scan` finds, and decodes what `decode_registers` decodes.
fn check_registers<F: Framing>(
    framing: &F,
    unit: UnitId,
    request: &Request<'_>,
    buf: &[u8],
    whole: Scan,
) {
    let (Request::ReadHoldingRegisters { count, .. } | Request::ReadInputRegisters { count, .. }) =
        *request
    else {
        return;
    };
    let mut fast = vec![0u16; usize::from(count)];
    let fast_result = scan_registers(framing, unit, request, buf, &mut fast);
    match (whole, fast_result) {
        (Scan::Found { start, len }, result) => {
            let mut slow = vec![0u16; usize::from(count)];
            let decoded =
                decode_registers(request, framing.pdu(&buf[start..start + len]), &mut slow);
            match (decoded, result) {
                (Ok(()), Ok(found)) => {
                    assert_eq!(found, whole, "register scan found another frame");
                    assert_eq!(fast, slow, "register scan decoded other values");
                }
                (Err(a), Err(b)) => assert_eq!(a, b, "register scan failed differently"),
                (a, b) => panic!("register scan {b:?} disagrees with decoding {a:?}"),
            }
        }
        (incomplete, result) => assert_eq!(
            result,
            Ok(incomplete),
            "register scan disagrees with the general scan"
        ),
    }
}

/// Dropping what a scan of a prefix called discardable loses no answer.
fn check_discard<F: Framing>(
    framing: &F,
    unit: UnitId,
    request: &Request<'_>,
    buf: &[u8],
    split: usize,
    whole: Scan,
) {
    let Scan::Incomplete { discard, .. } = framing.scan(unit, request, &buf[..split]) else {
        return;
    };
    assert!(discard <= split, "discards {discard} of {split} bytes");
    let Scan::Found { start, len } = whole else {
        return;
    };
    assert!(
        start >= discard,
        "the answer at {start} starts inside the {discard} bytes a prefix of {split} discarded"
    );
    assert_eq!(
        framing.scan(unit, request, &buf[discard..]),
        Scan::Found {
            start: start - discard,
            len
        },
        "scanning after the discarded bytes finds another frame"
    );
}

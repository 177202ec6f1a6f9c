//! Requests awaiting their answers over a framing whose answers name their request (MBAP
//! transaction ids): which received bytes answer which request. The part of pipelined batch
//! reads that needs no I/O, shared by the blocking and the async client.
//!
//! Each request in flight keeps a copy of the framing taken right after it was encoded, so the
//! framing's own scan (resynchronisation, late and foreign frames skipped, exceptions) decides
//! which bytes answer which request.

use crate::error::BusError;

use super::framing::{Framing, Scan};
use super::pdu::{decode_registers, Request};
use super::{RegisterRead, UnitId};

/// A request awaiting its answer.
#[derive(Clone, Copy)]
pub(crate) struct InFlight<F> {
    /// Index of its read in the batch.
    pub(crate) read: usize,
    pub(crate) request: Request<'static>,
    /// The framing as it was right after encoding the request: it recognises the answer.
    pub(crate) framing: F,
    pub(crate) answered: bool,
}

/// The answer to a request in flight: its frame is `rx[start..start + len]`.
pub(crate) struct Answer<F> {
    pub(crate) to: InFlight<F>,
    start: usize,
    len: usize,
}

/// Encodes every read of `reads` not done yet into `tx`, one after the other, and notes each in
/// `in_flight`; returns the bytes encoded.
pub(crate) fn encode_window<F: Framing>(
    framing: &mut F,
    unit: UnitId,
    reads: &[RegisterRead<'_>],
    tx: &mut [u8],
    in_flight: &mut [Option<InFlight<F>>],
) -> Result<usize, BusError> {
    let mut len = 0;
    let waiting = reads.iter().enumerate().filter(|(_, read)| !read.done);
    for (slot, (index, read)) in in_flight.iter_mut().zip(waiting) {
        let request = read_request(read)?;
        request.validate()?;
        let out = tx.get_mut(len..).unwrap_or_default();
        len += framing.encode_request(unit, &request, out)?;
        *slot = Some(InFlight {
            read: index,
            request,
            framing: *framing,
            answered: false,
        });
    }
    Ok(len)
}

/// Looks in `rx[..*rx_len]` for an answer to any request still awaiting one and marks that
/// request answered. Without one, drops the leading bytes no request in flight can use and
/// notes why the last candidate frame was rejected.
pub(crate) fn claim_answer<F: Framing>(
    unit: UnitId,
    in_flight: &mut [Option<InFlight<F>>],
    rx: &mut [u8],
    rx_len: &mut usize,
    rejected: &mut Option<&'static str>,
) -> Option<Answer<F>> {
    let received = &rx[..*rx_len];
    let mut useless = received.len();
    for entry in in_flight
        .iter_mut()
        .flatten()
        .filter(|entry| !entry.answered)
    {
        match entry.framing.scan(unit, &entry.request, received) {
            Scan::Found { start, len } => {
                entry.answered = true;
                return Some(Answer {
                    to: *entry,
                    start,
                    len,
                });
            }
            Scan::Incomplete {
                discard,
                rejected: why,
            } => {
                useless = useless.min(discard);
                *rejected = why.or(*rejected);
            }
        }
    }
    drop_front(rx, rx_len, useless);
    None
}

/// Decodes an answer into its read and removes its frame from `rx`, keeping the bytes around
/// it: they may answer other requests in flight.
pub(crate) fn take_answer<F: Framing>(
    answer: &Answer<F>,
    read: &mut RegisterRead<'_>,
    rx: &mut [u8],
    rx_len: &mut usize,
) -> Result<(), BusError> {
    let (request, framing) = (&answer.to.request, &answer.to.framing);
    let end = answer.start + answer.len;
    let frame = &rx[answer.start..end];
    let outcome = decode_registers(request, framing.pdu(frame), read.out);
    read.done = outcome.is_ok();
    rx.copy_within(end..*rx_len, answer.start);
    *rx_len -= answer.len;
    outcome
}

/// Drops the first `n` bytes of `rx[..*rx_len]`.
pub(crate) fn drop_front(rx: &mut [u8], rx_len: &mut usize, n: usize) {
    // Dropping all (an answer taken whole, or nothing received yet) moves nothing: no copy
    // call, twice per async read (docs/benchmarks.md, issue 30).
    if n >= *rx_len {
        *rx_len = 0;
        return;
    }
    rx.copy_within(n..*rx_len, 0);
    *rx_len -= n;
}

/// The request reading `read`.
pub(crate) fn read_request(read: &RegisterRead<'_>) -> Result<Request<'static>, BusError> {
    let count = u16::try_from(read.out.len())
        .map_err(|_| BusError::Unsupported("item count outside the Modbus limits"))?;
    Ok(Request::read_registers(read.table, read.start, count))
}

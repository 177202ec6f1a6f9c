//! What RTU and TCP framing have in common, so one blocking client drives both.

use crate::error::BusError;

use super::address::UnitId;
use super::pdu::Request;

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

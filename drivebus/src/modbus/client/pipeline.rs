//! Pipelined batch reads: over a framing whose answers name their request (MBAP transaction
//! ids), the reads of a batch go out in one write and their answers are matched as they come,
//! in any order — one round trip for the lot instead of one per request.
//!
//! Each request in flight keeps a copy of the framing taken right after it was encoded, so the
//! framing's own scan (resynchronisation, late and foreign frames skipped, exceptions) decides
//! which bytes answer which request.

use super::{count, ByteStream, Client};
use crate::error::BusError;
use crate::modbus::framing::{Framing, Scan};
use crate::modbus::pdu::{decode_registers, Request};
use crate::modbus::{RegisterRead, UnitId, MAX_IN_FLIGHT};

/// A request awaiting its answer.
#[derive(Clone, Copy)]
struct InFlight<F> {
    /// Index of its read in the batch.
    read: usize,
    request: Request<'static>,
    /// The framing as it was right after encoding the request: it recognises the answer.
    framing: F,
    answered: bool,
}

/// The answer to a request in flight: its frame is `rx[start..start + len]`.
struct Answer<F> {
    to: InFlight<F>,
    start: usize,
    len: usize,
}

impl<S: ByteStream, F: Framing> Client<S, F> {
    /// Reads the batch's reads not done yet, `config.max_in_flight` at a time. Each window is
    /// retried as the retry policy allows for reads, sending again only what is still missing.
    pub(super) fn read_pipelined(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        let window = self.config.max_in_flight.clamp(1, MAX_IN_FLIGHT);
        for reads in reads.chunks_mut(window) {
            let Some(first) = reads.iter().find(|read| !read.done) else {
                continue;
            };
            let attempts = self.checked_attempts(unit, &read_request(first)?, None)?;
            self.with_retries(attempts, |client| client.exchange_window(unit, reads))?;
        }
        Ok(())
    }

    /// Sends every read of `reads` not done yet in one write, then collects the answers until
    /// each is in or the timeout passes. An exception answers its read with an error; the
    /// other answers are still collected, and the first such error is returned.
    fn exchange_window(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        self.prepare_exchange(unit)?;
        let mut in_flight = [None; MAX_IN_FLIGHT];
        let mut len = 0;
        for (slot, (index, read)) in in_flight
            .iter_mut()
            .zip(reads.iter().enumerate().filter(|(_, read)| !read.done))
        {
            let request = read_request(read)?;
            request.validate()?;
            len += self
                .framing
                .encode_request(unit, &request, &mut self.tx[len..])?;
            *slot = Some(InFlight {
                read: index,
                request,
                framing: self.framing,
                answered: false,
            });
        }
        let deadline = self.send_encoded(len)?;
        let mut refused = Ok(());
        let mut rejected = None;
        let mut waiting = in_flight.iter().flatten().count();
        while waiting > 0 {
            match self.claim_answer(unit, &mut in_flight, &mut rejected) {
                Some(answer) => {
                    waiting -= 1;
                    let outcome = self.take_answer(&answer, &mut reads[answer.to.read]);
                    refused = refused.and(outcome);
                }
                None if self.receive_more(deadline)? == 0 => {
                    return Err(rejected.map_or(BusError::Timeout, BusError::Frame));
                }
                None => {}
            }
        }
        refused
    }

    /// Looks for an answer to any request still awaiting one and marks that request answered.
    /// Without one, drops the leading bytes no request in flight can use and notes why the last
    /// candidate frame was rejected.
    fn claim_answer(
        &mut self,
        unit: UnitId,
        in_flight: &mut [Option<InFlight<F>>],
        rejected: &mut Option<&'static str>,
    ) -> Option<Answer<F>> {
        let received = &self.rx[..self.rx_len];
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
        self.drop_front(useless);
        None
    }

    /// Decodes an answer into its read and removes its frame from the receive buffer, keeping
    /// the bytes around it: they may answer other requests in flight.
    fn take_answer(
        &mut self,
        answer: &Answer<F>,
        read: &mut RegisterRead<'_>,
    ) -> Result<(), BusError> {
        let (request, framing) = (&answer.to.request, &answer.to.framing);
        let end = answer.start + answer.len;
        let frame = &self.rx[answer.start..end];
        let outcome = decode_registers(request, framing.pdu(frame), read.out);
        read.done = outcome.is_ok();
        self.rx.copy_within(end..self.rx_len, answer.start);
        self.rx_len -= answer.len;
        outcome
    }
}

fn read_request(read: &RegisterRead<'_>) -> Result<Request<'static>, BusError> {
    Ok(Request::read_registers(
        read.table,
        read.start,
        count(read.out.len())?,
    ))
}

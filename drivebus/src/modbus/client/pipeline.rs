//! Pipelined batch reads: over a framing whose answers name their request (MBAP transaction
//! ids), the reads of a batch go out in one write and their answers are matched as they come,
//! in any order — one round trip for the lot instead of one per request.
//!
//! Which bytes answer which request is decided without I/O in `modbus::in_flight`, which the
//! async client shares.

use super::{ByteStream, Client};
use crate::error::BusError;
use crate::modbus::framing::Framing;
use crate::modbus::in_flight::{claim_answer, encode_window, read_request, take_answer};
use crate::modbus::{RegisterRead, UnitId, MAX_IN_FLIGHT};

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
        let len = encode_window(&mut self.framing, unit, reads, &mut self.tx, &mut in_flight)?;
        let deadline = self.send_encoded(len)?;
        let mut refused = Ok(());
        let mut rejected = None;
        let mut waiting = in_flight.iter().flatten().count();
        while waiting > 0 {
            let claimed = claim_answer(
                unit,
                &mut in_flight,
                &mut self.rx,
                &mut self.rx_len,
                &mut rejected,
            );
            match claimed {
                Some(answer) => {
                    waiting -= 1;
                    let read = &mut reads[answer.to.read];
                    let outcome = take_answer(&answer, read, &mut self.rx, &mut self.rx_len);
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
}

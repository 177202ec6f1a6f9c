//! What the tasks of one pipelined connection share, behind one mutex that is never held across
//! an `.await`: the requests in flight (one slot each, found by transaction id), the two halves
//! of the connection (taken by the task that writes or reads, put back when it is done), and
//! why the connection ended, if it did.

use core::task::Waker;
use std::boxed::Box;
use std::vec::Vec;

use crate::error::BusError;
use crate::modbus::pdu::MAX_PDU;
use crate::modbus::tcp::MAX_ADU;
use crate::modbus::UnitId;

/// Room for a little more than two ADUs, so a frame can complete behind another.
pub(super) const RX_CAPACITY: usize = 2 * MAX_ADU;

/// The read half and what it received that is not yet a whole frame.
#[derive(Debug)]
pub(super) struct ReadSide<R> {
    pub(super) stream: R,
    pub(super) rx: [u8; RX_CAPACITY],
    pub(super) len: usize,
}

/// Where a request stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Phase {
    /// Waiting for the write half.
    Writing,
    /// Sent; waiting for its answer (or for the read half, to read it).
    Awaiting,
}

/// One request in flight.
#[derive(Debug)]
pub(super) struct Slot {
    pub(super) transaction: u16,
    pub(super) unit: UnitId,
    pub(super) phase: Phase,
    pub(super) waker: Option<Waker>,
    /// The answer's PDU once the reader found it: its length in `pdu`.
    pub(super) answered: Option<usize>,
    pub(super) pdu: [u8; MAX_PDU],
}

/// The shared state.
#[derive(Debug)]
pub(super) struct State<R, W> {
    pub(super) slots: Vec<Slot>,
    pub(super) next_transaction: u16,
    /// `None` while a task writes.
    pub(super) writer: Option<W>,
    /// `None` while a task reads.
    pub(super) reader: Option<Box<ReadSide<R>>>,
    /// Set once the connection ended (closed by the peer, failed, a frame torn, or closed by
    /// [`TcpPipeline::close`](super::TcpPipeline::close)): every request gets it.
    pub(super) closed: Option<BusError>,
}

impl<R, W> State<R, W> {
    /// A slot for a new request to `unit`, with a transaction id no request in flight has.
    pub(super) fn open_slot(&mut self, unit: UnitId) -> Result<u16, BusError> {
        if let Some(closed) = &self.closed {
            return Err(closed.clone());
        }
        if self.slots.len() > usize::from(u16::MAX) {
            return Err(BusError::Unsupported(
                "65,536 requests in flight on one connection",
            ));
        }
        // Fewer than 65,536 are in flight, so a free id is found.
        let mut transaction = self.next_transaction;
        while self.slots.iter().any(|s| s.transaction == transaction) {
            transaction = transaction.wrapping_add(1);
        }
        self.next_transaction = transaction.wrapping_add(1);
        self.slots.push(Slot {
            transaction,
            unit,
            phase: Phase::Writing,
            waker: None,
            answered: None,
            pdu: [0; MAX_PDU],
        });
        Ok(transaction)
    }

    /// The slot of `transaction`, if its request is still in flight.
    pub(super) fn slot(&mut self, transaction: u16) -> Option<&mut Slot> {
        self.slots.iter_mut().find(|s| s.transaction == transaction)
    }

    /// Forgets `transaction`: its answer, if it still comes, is dropped.
    pub(super) fn close_slot(&mut self, transaction: u16) {
        self.slots.retain(|s| s.transaction != transaction);
    }

    /// Files the answer `pdu` of `transaction` from `unit` and wakes its task; an answer no
    /// request waits for (a dropped or timed-out one's, or another unit's) is dropped.
    pub(super) fn deliver(&mut self, transaction: u16, unit: UnitId, pdu: &[u8]) {
        let Some(slot) = self.slot(transaction) else {
            return;
        };
        let Some(to) = slot.pdu.get_mut(..pdu.len()) else {
            return;
        };
        if slot.unit != unit || slot.phase != Phase::Awaiting {
            return;
        }
        to.copy_from_slice(pdu);
        slot.answered = Some(pdu.len());
        if let Some(waker) = slot.waker.take() {
            waker.wake();
        }
    }

    /// Wakes the tasks in `phase` (still without an answer): one of them takes the half just
    /// put back.
    pub(super) fn wake(&mut self, phase: Phase) {
        for slot in &mut self.slots {
            if slot.phase == phase && slot.answered.is_none() {
                if let Some(waker) = slot.waker.take() {
                    waker.wake();
                }
            }
        }
    }

    /// Ends the connection with `error` (the first reason is kept) and wakes every task.
    pub(super) fn close(&mut self, error: BusError) {
        self.closed.get_or_insert(error);
        for slot in &mut self.slots {
            if let Some(waker) = slot.waker.take() {
                waker.wake();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state() -> State<(), ()> {
        State {
            slots: Vec::new(),
            next_transaction: 0xFFFF,
            writer: Some(()),
            reader: None,
            closed: None,
        }
    }

    #[test]
    fn transaction_ids_wrap_and_skip_the_ones_in_flight() {
        let mut state = state();
        assert_eq!(state.open_slot(UnitId(1)), Ok(0xFFFF));
        assert_eq!(state.open_slot(UnitId(1)), Ok(0));
        state.next_transaction = 0xFFFF;
        assert_eq!(
            state.open_slot(UnitId(1)),
            Ok(1),
            "0xFFFF and 0 are in flight"
        );
        state.close_slot(0);
        state.next_transaction = 0;
        assert_eq!(state.open_slot(UnitId(1)), Ok(0), "given up, free again");
    }

    #[test]
    fn an_answer_is_filed_only_for_its_request() {
        let mut state = state();
        let tid = state.open_slot(UnitId(3)).unwrap();
        let pdu = [0x03, 2, 0x12, 0x34];
        // Not sent yet: an answer cannot be its own.
        state.deliver(tid, UnitId(3), &pdu);
        assert_eq!(state.slot(tid).unwrap().answered, None);
        state.slot(tid).unwrap().phase = Phase::Awaiting;
        // Another transaction's, another unit's: dropped.
        state.deliver(tid.wrapping_add(1), UnitId(3), &pdu);
        state.deliver(tid, UnitId(4), &pdu);
        assert_eq!(state.slot(tid).unwrap().answered, None);
        state.deliver(tid, UnitId(3), &pdu);
        let slot = state.slot(tid).unwrap();
        assert_eq!(slot.answered, Some(4));
        assert_eq!(slot.pdu[..4], pdu);
    }

    #[test]
    fn a_closed_pipeline_refuses_new_requests_with_its_reason() {
        let mut state = state();
        state.close(BusError::Closed);
        state.close(BusError::Timeout);
        assert_eq!(state.open_slot(UnitId(1)), Err(BusError::Closed));
    }
}

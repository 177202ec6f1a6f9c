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

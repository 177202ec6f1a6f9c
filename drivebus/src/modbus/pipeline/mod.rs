//! Modbus TCP pipelining across handles (features `async` and `std`): one TCP connection shared
//! by clones of a [`TcpPipeline`], each clone a handle of its own task, with all their requests
//! in flight at once. Each request has its own transaction id; answers are matched by it, in
//! whatever order the server sends them.
//!
//! No driver future and no runtime: the waiting tasks take turns pumping. The task that sends
//! takes the write half for its one frame; a task waiting for its answer either finds it filed
//! already or, if no other task is reading, takes the read half and reads, filing every answer
//! it finds under its transaction id (and waking its task) until its own is in; then it hands
//! the read half to the next waiting task. The shared state sits behind one mutex that is never
//! held across an `.await`.
//!
//! * A request dropped mid-flight (its future dropped, or timed out) gives up its transaction
//!   id: its answer, when it comes, is dropped, and no later request can take it for its own.
//!   Dropped in the middle of sending its frame, it leaves a torn frame on the connection: the
//!   pipeline is then closed ([`BusError::Closed`] to every request; open a new connection).
//! * Each handle (clone) keeps one alarm for its requests' timeouts, moved at each request:
//!   cheaper than a timer armed afresh per request (docs/benchmarks.md, issue 30).
//! * The connection closed by the server, or failing, gives every waiting and later request a
//!   typed error ([`BusError::Closed`], [`BusError::Io`]), never a hang; so does
//!   [`TcpPipeline::close`] to every request that has not yet reached the reading (one that is
//!   reading ends at its timeout).
//!
//! The pipeline is an [`AsyncRegisterBus`]: a generated drive handle works on a clone unchanged
//! (`Smartris::new_async(ModbusLink::new(pipeline.clone(), ..))`), and a handle's batch
//! (`read_many`) has its reads in flight at once as well (`batch.rs`). Requests are not repeated
//! (no retry policy): with several in flight, a repeat could overtake a later request.

mod batch;
mod state;
#[cfg(feature = "tokio")]
mod tokio;

use core::future::poll_fn;
use core::task::Poll;
use core::time::Duration;
use std::boxed::Box;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::vec::Vec;

use embedded_io_async::{Read, Write};

use self::state::{Phase, ReadSide, State, RX_CAPACITY};
use super::async_client::{count, stream_error};
use super::in_flight::drop_front;
use super::pdu::{decode_registers, decode_response, Request, MAX_PDU};
use super::tcp::{encode_request, Header, HEADER_LEN, MAX_ADU};
use super::{AsyncRegisterBus, RegisterRead, Table, UnitId};
use crate::asynch::{within_alarm, Timer};
use crate::error::BusError;

#[cfg(feature = "tokio")]
pub use self::tokio::TokioPipeline;

/// One Modbus TCP connection shared by its clones, their requests pipelined: read half `R`,
/// write half `W`, timed by `T`.
#[derive(Debug)]
pub struct TcpPipeline<R, W, T: Timer> {
    shared: Arc<Shared<R, W, T>>,
    /// This handle's answer timeout, kept from one request to the next and moved at each.
    alarm: T::Alarm,
}

#[derive(Debug)]
struct Shared<R, W, T> {
    state: Mutex<State<R, W>>,
    timer: T,
    timeout: Duration,
}

/// A clone has an alarm of its own (a clone is another task's handle).
impl<R, W, T: Timer> Clone for TcpPipeline<R, W, T> {
    fn clone(&self) -> Self {
        Self {
            shared: Arc::clone(&self.shared),
            alarm: self.shared.timer.alarm(),
        }
    }
}

impl<R, W, T> Shared<R, W, T> {
    fn lock(&self) -> MutexGuard<'_, State<R, W>> {
        // A task that panicked holding the lock left the state consistent: every change is
        // one assignment or one `Vec` operation.
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

/// What a task waiting for its answer gets its turn for.
enum Turn<R> {
    /// Its answer is in: the PDU's length.
    Answered(usize),
    /// The read half, to read on.
    Read(Box<ReadSide<R>>),
}

impl<R: Read, W: Write, T: Timer> TcpPipeline<R, W, T> {
    /// A pipeline over the two halves of one connected stream; each request (its sending and
    /// its answer) must complete within `timeout`.
    pub fn new(reader: R, writer: W, timer: T, timeout: Duration) -> Self {
        let reader = Box::new(ReadSide {
            stream: reader,
            rx: [0; RX_CAPACITY],
            len: 0,
        });
        let state = State {
            slots: Vec::new(),
            next_transaction: 1,
            writer: Some(writer),
            reader: Some(reader),
            closed: None,
        };
        Self {
            alarm: timer.alarm(),
            shared: Arc::new(Shared {
                state: Mutex::new(state),
                timer,
                timeout,
            }),
        }
    }

    /// Closes the pipeline: every request not yet reading, and every later one, gets
    /// [`BusError::Closed`].
    pub fn close(&self) {
        self.shared.lock().close(BusError::Closed);
    }

    /// How many requests are in flight (sent or waiting to be).
    pub fn in_flight(&self) -> usize {
        self.shared.lock().slots.len()
    }

    /// Sends `request` to `unit` and hands its answer's PDU to `answer`, within the timeout.
    async fn exchange<A>(
        &mut self,
        unit: UnitId,
        request: &Request<'_>,
        answer: impl FnOnce(&[u8]) -> Result<A, BusError>,
    ) -> Result<A, BusError> {
        request.validate()?;
        let shared = &*self.shared;
        let transaction = shared.lock().open_slot(unit)?;
        let _slot = SlotGuard {
            pipeline: shared,
            transaction,
        };
        let mut frame = [0u8; MAX_ADU];
        let len = encode_request(transaction, unit, request, &mut frame)?;
        let mut pdu = [0u8; MAX_PDU];
        let pdu_len = within_alarm(&mut self.alarm, shared.timeout, async {
            shared.send(transaction, &frame[..len]).await?;
            shared.await_answer(transaction, &mut pdu).await
        })
        .await
        .map_err(|_| BusError::Timeout)??;
        answer(&pdu[..pdu_len])
    }
}

impl<R: Read, W: Write, T> Shared<R, W, T> {
    /// Waits for the write half, then sends `frame` whole.
    async fn send(&self, transaction: u16, frame: &[u8]) -> Result<(), BusError> {
        let writer = poll_fn(|cx| {
            let mut state = self.lock();
            if let Some(closed) = &state.closed {
                return Poll::Ready(Err(closed.clone()));
            }
            let writer = state.writer.take();
            let Some(slot) = state.slot(transaction) else {
                return Poll::Ready(Err(BusError::Closed));
            };
            match writer {
                Some(writer) => {
                    // Before the first byte: the answer may be read before `send` returns.
                    slot.phase = Phase::Awaiting;
                    Poll::Ready(Ok(writer))
                }
                None => {
                    slot.waker = Some(cx.waker().clone());
                    Poll::Pending
                }
            }
        })
        .await?;
        let mut guard = WriterGuard {
            pipeline: self,
            writer: Some(writer),
            whole: false,
        };
        if let Some(writer) = guard.writer.as_mut() {
            let sent = match writer.write_all(frame).await {
                Ok(()) => writer.flush().await,
                Err(error) => Err(error),
            };
            if let Err(error) = sent.map_err(stream_error) {
                self.lock().close(error.clone());
                return Err(error);
            }
        }
        guard.whole = true;
        Ok(())
    }

    /// Waits for the answer of `transaction`, reading for every task while no other does;
    /// copies its PDU into `out` and returns its length.
    async fn await_answer(
        &self,
        transaction: u16,
        out: &mut [u8; MAX_PDU],
    ) -> Result<usize, BusError> {
        loop {
            let turn = poll_fn(|cx| self.poll_turn(cx, transaction, out)).await?;
            match turn {
                Turn::Answered(len) => return Ok(len),
                Turn::Read(side) => {
                    let mut guard = ReaderGuard {
                        pipeline: self,
                        side: Some(side),
                    };
                    if let Some(side) = guard.side.as_mut() {
                        self.pump(side, transaction).await?;
                    }
                }
            }
        }
    }

    /// The answer, if filed; else the read half, if free; else waits for either.
    fn poll_turn(
        &self,
        cx: &mut core::task::Context<'_>,
        transaction: u16,
        out: &mut [u8; MAX_PDU],
    ) -> Poll<Result<Turn<R>, BusError>> {
        let mut state = self.lock();
        let closed = state.closed.clone();
        let reader = match state.slot(transaction) {
            None => return Poll::Ready(Err(BusError::Closed)),
            Some(slot) => match slot.answered {
                Some(len) => {
                    let len = len.min(MAX_PDU);
                    out[..len].copy_from_slice(&slot.pdu[..len]);
                    return Poll::Ready(Ok(Turn::Answered(len)));
                }
                None if closed.is_some() => None,
                None => {
                    slot.waker = Some(cx.waker().clone());
                    Some(())
                }
            },
        };
        match (closed, reader.and_then(|()| state.reader.take())) {
            (Some(closed), _) => Poll::Ready(Err(closed)),
            (None, Some(side)) => Poll::Ready(Ok(Turn::Read(side))),
            (None, None) => Poll::Pending,
        }
    }

    /// Reads and files answers until the answer of `transaction` is in.
    async fn pump(&self, side: &mut ReadSide<R>, transaction: u16) -> Result<(), BusError> {
        loop {
            let mine_in = {
                let mut state = self.lock();
                file_answers(&mut state, side);
                state
                    .slot(transaction)
                    .is_none_or(|slot| slot.answered.is_some())
            };
            if mine_in {
                return Ok(());
            }
            if side.len == side.rx.len() {
                // Unreachable with a well-behaved server (a frame is shorter than the buffer).
                side.len = 0;
            }
            let got = side.stream.read(&mut side.rx[side.len..]).await;
            match got.map_err(stream_error) {
                Ok(0) => return Err(self.ended(BusError::Closed)),
                Ok(n) => side.len += n,
                Err(error) => return Err(self.ended(error)),
            }
        }
    }

    /// Closes the pipeline with `error`; returns the error it ended with.
    fn ended(&self, error: BusError) -> BusError {
        let mut state = self.lock();
        state.close(error);
        state.closed.clone().unwrap_or(BusError::Closed)
    }
}

/// Files every whole frame at the start of `side`'s buffer under its transaction id. A header
/// no frame can have means the stream is out of step: what was received is dropped (the
/// requests it held time out).
fn file_answers<R, W>(state: &mut State<R, W>, side: &mut ReadSide<R>) {
    while side.len >= HEADER_LEN {
        let Ok(header) = Header::parse(&side.rx[..side.len]) else {
            side.len = 0;
            return;
        };
        let end = HEADER_LEN + header.pdu_len;
        let Some(pdu) = side.rx.get(HEADER_LEN..end).filter(|_| end <= side.len) else {
            return;
        };
        state.deliver(header.transaction, header.unit, pdu);
        drop_front(&mut side.rx, &mut side.len, end);
    }
}

/// Forgets its request when the request ends, however it ends.
struct SlotGuard<'a, R, W, T> {
    pipeline: &'a Shared<R, W, T>,
    transaction: u16,
}

impl<R, W, T> Drop for SlotGuard<'_, R, W, T> {
    fn drop(&mut self) {
        let mut state = self.pipeline.lock();
        state.close_slot(self.transaction);
    }
}

/// Puts the write half back and wakes a task waiting for it; a frame not sent whole closes the
/// pipeline (the server would read the next frame out of step).
struct WriterGuard<'a, R, W, T> {
    pipeline: &'a Shared<R, W, T>,
    writer: Option<W>,
    whole: bool,
}

impl<R, W, T> Drop for WriterGuard<'_, R, W, T> {
    fn drop(&mut self) {
        let mut state = self.pipeline.lock();
        state.writer = self.writer.take();
        if !self.whole {
            state.close(BusError::Closed);
        }
        state.wake(Phase::Writing);
    }
}

/// Puts the read half back (with what it received) and wakes the tasks waiting for answers:
/// one of them reads next.
struct ReaderGuard<'a, R, W, T> {
    pipeline: &'a Shared<R, W, T>,
    side: Option<Box<ReadSide<R>>>,
}

impl<R, W, T> Drop for ReaderGuard<'_, R, W, T> {
    fn drop(&mut self) {
        let mut state = self.pipeline.lock();
        state.reader = self.side.take();
        state.wake(Phase::Awaiting);
    }
}

impl<R: Read, W: Write, T: Timer> AsyncRegisterBus for TcpPipeline<R, W, T> {
    async fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        let request = Request::read_registers(table, start, count(out.len())?);
        self.exchange(unit, &request, |pdu| decode_registers(&request, pdu, out))
            .await
    }

    async fn write_register(
        &mut self,
        unit: UnitId,
        address: u16,
        value: u16,
    ) -> Result<(), BusError> {
        let request = Request::WriteSingleRegister { address, value };
        self.exchange(unit, &request, |pdu| {
            decode_response(&request, pdu).map(drop)
        })
        .await
    }

    async fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        let request = Request::write_registers(start, values);
        self.exchange(unit, &request, |pdu| {
            decode_response(&request, pdu).map(drop)
        })
        .await
    }

    /// The batch's reads are in flight at once (a window of [`MAX_IN_FLIGHT`](super::MAX_IN_FLIGHT)
    /// at a time), their answers matched by transaction id.
    async fn read_register_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        self.read_batch(unit, reads).await
    }
}

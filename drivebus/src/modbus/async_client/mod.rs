//! Async Modbus clients over `embedded-io-async` byte streams (feature `async`): one
//! request/response engine, [`AsyncClient`], with MBAP or RTU framing, its time from a
//! [`Timer`].
//!
//! | client | framing | stream |
//! | --- | --- | --- |
//! | [`AsyncTcpClient`] | MBAP | TCP (`tokio::net::TcpStream` through `tokio::connect_tcp`) |
//! | [`AsyncRtuClient`] (`modbus-core`) | RTU | serial port, or a TCP connection to an RTU gateway (RTU over TCP) |
//!
//! The framings are the sans-I/O ones the blocking clients use; so is the matching of
//! pipelined answers to their requests (`modbus::in_flight`). Only the waiting differs.
//!
//! **Cancellation.** Dropping a request's future at any point leaves the client usable:
//! * Modbus TCP: the dropped request's answer, when it comes, carries a transaction id no later
//!   request has, and is skipped. A request dropped in the middle of sending its frame leaves a
//!   torn frame on the connection: the client then answers every request with
//!   [`BusError::Closed`] (open a new connection).
//! * RTU: before the next request the line is resynchronised: what arrives within one
//!   timeout (the dropped request's late answer) is read and dropped, then the inter-frame
//!   silence is waited out. A timed-out request is treated the same way.
//!
//! A stream that ends (the peer closed the connection) under a pending request gives
//! [`BusError::Closed`], never a hang; a stream error gives [`BusError::Io`] (with `std`).

use core::time::Duration;

use embedded_io_async::{Read, Write};

use crate::asynch::{within, within_alarm, Timer};
use crate::error::BusError;

use super::framing::{scan_registers, Framing, Scan};
use super::in_flight::{claim_answer, drop_front, encode_window, read_request, take_answer};
use super::pdu::Request;
use super::retry::{is_transient, RetryPolicy};
use super::tcp::{TcpFraming, MAX_ADU};
use super::{AsyncRegisterBus, RegisterRead, Table, UnitId, MAX_IN_FLIGHT};

#[cfg(feature = "tokio")]
pub mod tokio;

/// How an async client times, retries and paces requests.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AsyncClientConfig {
    /// How long to wait for the answer to one attempt.
    pub timeout: Duration,
    /// Which failed requests are repeated.
    pub retry: RetryPolicy,
    /// Silence kept before every request (t3.5 and the device's turnaround on RTU; usually
    /// zero on TCP). A `Timer` tells no time, so the whole gap is waited before each request,
    /// however long the line has been idle (the blocking client waits only what is left).
    pub idle_gap: Duration,
    /// How many reads of a batch may await their answers at once (at most
    /// [`MAX_IN_FLIGHT`]); above 1, Modbus TCP sends them together. Default 1, as the blocking
    /// client: many servers handle one request at a time.
    pub max_in_flight: usize,
}

impl Default for AsyncClientConfig {
    fn default() -> Self {
        Self {
            timeout: Duration::from_secs(1),
            retry: RetryPolicy::reads(2),
            idle_gap: Duration::ZERO,
            max_in_flight: 1,
        }
    }
}

/// Room for a little more than two ADUs, so a frame can complete behind garbage.
const RX_CAPACITY: usize = 2 * MAX_ADU;

/// Where the last request stopped: what the next one must clean up first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Left {
    /// Nothing: the last request completed with its answer.
    Clean,
    /// In the middle of sending its frame (its future was dropped there).
    Sending,
    /// Sent, its answer not taken: dropped while waiting, or timed out.
    Awaiting,
}

/// An async Modbus client over stream `S` with framing `F`, timed by `T`.
#[derive(Debug)]
pub struct AsyncClient<S, F, T: Timer> {
    io: Io<S, F>,
    timer: T,
    /// The answer timeout, kept from one request to the next and moved at each: cheaper than
    /// a timer armed afresh per request (docs/benchmarks.md, issue 30).
    alarm: T::Alarm,
    config: AsyncClientConfig,
}

/// The stream and its buffers: what the timer's timeouts wrap.
#[derive(Debug)]
struct Io<S, F> {
    stream: S,
    framing: F,
    tx: [u8; MAX_ADU],
    rx: [u8; RX_CAPACITY],
    rx_len: usize,
    /// How many bytes at the front of the receive buffer are the answer the last request took
    /// (kept until the next request: a write's answer is decoded after the exchange).
    taken: usize,
    left: Left,
}

/// An async Modbus TCP (MBAP) client.
pub type AsyncTcpClient<S, T> = AsyncClient<S, TcpFraming, T>;
/// An async Modbus RTU client, over a serial port or a TCP connection to an RTU gateway.
#[cfg(feature = "modbus-core")]
pub type AsyncRtuClient<S, T> = AsyncClient<S, super::rtu::RtuFraming, T>;

impl<S: Read + Write, T: Timer> AsyncClient<S, TcpFraming, T> {
    /// A Modbus TCP client over a connected stream.
    pub fn tcp(stream: S, timer: T, config: AsyncClientConfig) -> Self {
        Self::new(stream, TcpFraming::default(), timer, config)
    }
}

#[cfg(feature = "modbus-core")]
impl<S: Read + Write, T: Timer> AsyncClient<S, super::rtu::RtuFraming, T> {
    /// A Modbus RTU client over a serial line or an RTU-over-TCP gateway connection; set
    /// `config.idle_gap` to the line's t3.5 (`modbus::rtu::Timing`) plus the device's
    /// turnaround.
    pub fn rtu(stream: S, timer: T, config: AsyncClientConfig) -> Self {
        Self::new(stream, super::rtu::RtuFraming, timer, config)
    }
}

impl<S: Read + Write, F: Framing, T: Timer> AsyncClient<S, F, T> {
    /// A client sending over `stream` with `framing`.
    pub fn new(stream: S, framing: F, timer: T, config: AsyncClientConfig) -> Self {
        Self {
            io: Io {
                stream,
                framing,
                tx: [0; MAX_ADU],
                rx: [0; RX_CAPACITY],
                rx_len: 0,
                taken: 0,
                left: Left::Clean,
            },
            alarm: timer.alarm(),
            timer,
            config,
        }
    }

    /// The timing and retry settings.
    pub fn config_mut(&mut self) -> &mut AsyncClientConfig {
        &mut self.config
    }

    /// The underlying stream.
    pub fn stream_mut(&mut self) -> &mut S {
        &mut self.io.stream
    }

    /// Reads `out.len()` registers in one request, retried as the policy allows for reads.
    async fn read_into(
        &mut self,
        unit: UnitId,
        request: Request<'_>,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        // The answer is decoded into `out` as it is found: one pass over the frame.
        self.execute(unit, &request, |framing, buf| {
            scan_registers(framing, unit, &request, buf, out)
        })
        .await
        .map(drop)
    }

    /// Sends a write and checks its answer; repeated as the policy allows for it.
    async fn write(&mut self, unit: UnitId, request: Request<'_>) -> Result<(), BusError> {
        let frame = self
            .execute(unit, &request, |framing, buf| {
                Ok(framing.scan(unit, &request, buf))
            })
            .await?;
        let pdu = self.io.framing.pdu(&self.io.rx[frame]);
        super::pdu::decode_response(&request, pdu).map(drop)
    }

    /// Checks `request`, then exchanges it as often as the retry policy allows while it fails
    /// transiently; returns where the answer's frame is in the receive buffer.
    async fn execute(
        &mut self,
        unit: UnitId,
        request: &Request<'_>,
        mut scan: impl FnMut(&F, &[u8]) -> Result<Scan, BusError>,
    ) -> Result<core::ops::Range<usize>, BusError> {
        request.validate()?;
        let attempts = self.config.retry.attempts(request, None);
        let mut tried = 1;
        loop {
            match self.exchange(unit, request, &mut scan).await {
                Err(error) if tried < attempts && is_transient(&error) => tried += 1,
                outcome => return outcome,
            }
        }
    }

    /// One request and its answer, found by `scan` in the bytes received so far (and decoded
    /// on the way); returns where the answer's frame is in the receive buffer.
    async fn exchange(
        &mut self,
        unit: UnitId,
        request: &Request<'_>,
        mut scan: impl FnMut(&F, &[u8]) -> Result<Scan, BusError>,
    ) -> Result<core::ops::Range<usize>, BusError> {
        self.resynchronise().await?;
        let len = self
            .io
            .framing
            .encode_request(unit, request, &mut self.io.tx)?;
        self.io.send(len).await?;
        let mut rejected = None;
        let io = &mut self.io;
        let answer = within_alarm(&mut self.alarm, self.config.timeout, async {
            loop {
                match scan(&io.framing, &io.rx[..io.rx_len])? {
                    Scan::Found { start, len } => return Ok(start..start + len),
                    Scan::Incomplete {
                        discard,
                        rejected: why,
                    } => {
                        rejected = why.or(rejected);
                        drop_front(&mut io.rx, &mut io.rx_len, discard);
                    }
                }
                io.receive().await?;
            }
        })
        .await;
        let frame = answer.map_err(|_| rejected.map_or(BusError::Timeout, BusError::Frame))??;
        self.io.left = Left::Clean;
        self.io.taken = frame.end;
        Ok(frame)
    }

    /// Reads of a batch kept in flight together (MBAP only), `max_in_flight` at a time.
    async fn read_pipelined(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        let window = self.config.max_in_flight.clamp(1, MAX_IN_FLIGHT);
        for reads in reads.chunks_mut(window) {
            let Some(first) = reads.iter().find(|read| !read.done) else {
                continue;
            };
            let attempts = self.config.retry.attempts(&read_request(first)?, None);
            let mut tried = 1;
            loop {
                match self.exchange_window(unit, reads).await {
                    Err(error) if tried < attempts && is_transient(&error) => tried += 1,
                    outcome => break outcome?,
                }
            }
        }
        Ok(())
    }

    /// Sends the window's reads not done yet in one write, then collects their answers in any
    /// order until each is in or the timeout passes.
    async fn exchange_window(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        self.resynchronise().await?;
        let mut in_flight = [None; MAX_IN_FLIGHT];
        let io = &mut self.io;
        let len = encode_window(&mut io.framing, unit, reads, &mut io.tx, &mut in_flight)?;
        io.send(len).await?;
        let mut rejected = None;
        let mut refused = Ok(());
        let mut waiting = in_flight.iter().flatten().count();
        let io = &mut self.io;
        let collected = within_alarm(&mut self.alarm, self.config.timeout, async {
            while waiting > 0 {
                let (rx, rx_len) = (&mut io.rx, &mut io.rx_len);
                match claim_answer(unit, &mut in_flight, rx, rx_len, &mut rejected) {
                    Some(answer) => {
                        waiting -= 1;
                        let read = &mut reads[answer.to.read];
                        refused = refused.clone().and(take_answer(&answer, read, rx, rx_len));
                    }
                    None => io.receive().await?,
                }
            }
            Ok::<(), BusError>(())
        })
        .await;
        collected.map_err(|_| rejected.map_or(BusError::Timeout, BusError::Frame))??;
        self.io.left = Left::Clean;
        refused
    }

    /// Cleans up after a request that did not complete (dropped, or timed out), then keeps
    /// the idle gap: the start of every request.
    async fn resynchronise(&mut self) -> Result<(), BusError> {
        // The last answer is no stale frame: dropped unseen, so a timeout now is reported as
        // one (as the blocking client does), not as a transaction id that does not match.
        let io = &mut self.io;
        drop_front(&mut io.rx, &mut io.rx_len, core::mem::take(&mut io.taken));
        match self.io.left {
            Left::Sending if F::TAGGED_ANSWERS => return Err(BusError::Closed),
            // RTU answers carry no tag: a late answer must not pass for the next one.
            Left::Sending | Left::Awaiting if !F::TAGGED_ANSWERS => {
                self.io.rx_len = 0;
                self.io.drain(&self.timer, self.config.timeout).await?;
            }
            // MBAP: stale answers stay in the buffer, skipped by their transaction ids.
            _ => {}
        }
        self.io.left = Left::Clean;
        if !self.config.idle_gap.is_zero() {
            self.timer.sleep(self.config.idle_gap).await;
        }
        if !F::TAGGED_ANSWERS {
            self.io.rx_len = 0;
        }
        Ok(())
    }
}

impl<S: Read + Write, F: Framing> Io<S, F> {
    /// Sends the `len` bytes encoded in the transmit buffer. Until it completes, a dropped
    /// future leaves [`Left::Sending`]; after, [`Left::Awaiting`] until the answer is taken.
    async fn send(&mut self, len: usize) -> Result<(), BusError> {
        self.left = Left::Sending;
        self.stream
            .write_all(&self.tx[..len])
            .await
            .map_err(stream_error)?;
        self.stream.flush().await.map_err(stream_error)?;
        self.left = Left::Awaiting;
        Ok(())
    }

    /// Receives more bytes into the receive buffer; the stream's end is [`BusError::Closed`].
    async fn receive(&mut self) -> Result<(), BusError> {
        if self.rx_len == self.rx.len() {
            // Unreachable with well-behaved framings (a pending frame is shorter than an ADU).
            drop_front(&mut self.rx, &mut self.rx_len, RX_CAPACITY / 2);
        }
        let got = self
            .stream
            .read(&mut self.rx[self.rx_len..])
            .await
            .map_err(stream_error)?;
        if got == 0 {
            return Err(BusError::Closed);
        }
        self.rx_len += got;
        Ok(())
    }

    /// Reads and drops what arrives until the line has been silent for `silence`: the late
    /// answer of a request that did not complete. Bounded: a line that never falls silent is
    /// given up on after [`MAX_DRAIN`] bytes.
    async fn drain(&mut self, timer: &impl Timer, silence: Duration) -> Result<(), BusError> {
        let mut dropped = 0;
        while dropped < MAX_DRAIN {
            match within(timer, silence, self.stream.read(&mut self.rx)).await {
                Err(_silent) => return Ok(()),
                Ok(Ok(0)) => return Err(BusError::Closed),
                Ok(Ok(n)) => dropped += n,
                Ok(Err(error)) => return Err(stream_error(error)),
            }
        }
        Ok(())
    }
}

/// Most bytes one resynchronisation drops.
const MAX_DRAIN: usize = 4 * RX_CAPACITY;

/// A stream's error as a bus error.
pub(super) fn stream_error(error: impl embedded_io_async::Error) -> BusError {
    #[cfg(feature = "std")]
    {
        use embedded_io_async::ErrorKind as Kind;
        use std::io::ErrorKind as Std;
        let kind = match error.kind() {
            Kind::NotFound => Std::NotFound,
            Kind::PermissionDenied => Std::PermissionDenied,
            Kind::ConnectionRefused => Std::ConnectionRefused,
            Kind::ConnectionReset => Std::ConnectionReset,
            Kind::ConnectionAborted => Std::ConnectionAborted,
            Kind::NotConnected => Std::NotConnected,
            Kind::BrokenPipe => Std::BrokenPipe,
            Kind::TimedOut => Std::TimedOut,
            Kind::Interrupted => Std::Interrupted,
            _ => Std::Other,
        };
        BusError::Io(kind)
    }
    #[cfg(not(feature = "std"))]
    {
        let _ = error;
        BusError::Frame("the byte stream failed")
    }
}

/// A register count as a Modbus quantity.
pub(super) fn count(items: usize) -> Result<u16, BusError> {
    u16::try_from(items).map_err(|_| BusError::Unsupported("item count outside the Modbus limits"))
}

impl<S: Read + Write, F: Framing, T: Timer> AsyncRegisterBus for AsyncClient<S, F, T> {
    async fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        let request = Request::read_registers(table, start, count(out.len())?);
        self.read_into(unit, request, out).await
    }

    async fn write_register(
        &mut self,
        unit: UnitId,
        address: u16,
        value: u16,
    ) -> Result<(), BusError> {
        self.write(unit, Request::WriteSingleRegister { address, value })
            .await
    }

    async fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        self.write(unit, Request::write_registers(start, values))
            .await
    }

    async fn read_register_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        if F::TAGGED_ANSWERS && self.config.max_in_flight > 1 {
            return self.read_pipelined(unit, reads).await;
        }
        for read in reads.iter_mut().filter(|read| !read.done) {
            self.read_registers(unit, read.table, read.start, read.out)
                .await?;
            read.done = true;
        }
        Ok(())
    }
}

//! An async RS-232 host over any `embedded-io-async` byte stream: the sans-I/O [`Exchange`]
//! the blocking `rs232::client::Rs232Client` drives, driven with a [`Timer`].

use core::time::Duration;

use super::data::{Answer, Request};
use super::exchange::Exchange;
use super::telegram::TELEGRAM_LEN;
use super::{AsyncTelegramBus, LoopMode, StationId};
use crate::asynch::io_error::{bus_error, closed};
use crate::asynch::race::ready_now;
use crate::asynch::{within, within_alarm, Timer};
use crate::error::BusError;

/// Default time the drive has to answer (as the blocking host's default).
pub const DEFAULT_TIMEOUT: Duration = Duration::from_millis(500);

/// Default silence that closes an exchange whose future was dropped or that failed: the line
/// must stay quiet this long before the next request goes out (a 10-byte telegram takes under
/// 3 ms at 38400 Bd).
pub const DEFAULT_QUIET: Duration = Duration::from_millis(20);

/// Most reads spent draining stale input before a request, so a babbling line cannot hold the
/// host back forever (the request then fails on the noise instead).
const MAX_DRAIN_READS: usize = 64;

/// An async RS-232 host: one [`Exchange`] at a time over a byte stream.
///
/// Cancellation: an exchange whose future was dropped (or that failed) is closed before the
/// next one: stale bytes are drained until the line has been quiet for the quiet time, so a
/// late answer is never read as the next request's. Bytes already buffered are dropped before
/// every request, as the blocking host does. Nothing is repeated on its own.
#[derive(Debug)]
pub struct AsyncRs232Client<S, T: Timer> {
    stream: S,
    timer: T,
    /// The answer timeout, kept from one exchange to the next and moved at each: cheaper than
    /// a timer armed afresh per exchange (docs/benchmarks.md, issue 30).
    alarm: T::Alarm,
    mode: LoopMode,
    timeout: Duration,
    quiet: Duration,
    /// An exchange began and did not end with its answer: the line may still carry its bytes.
    open: bool,
}

impl<S: embedded_io_async::Read + embedded_io_async::Write, T: Timer> AsyncRs232Client<S, T> {
    /// A host on `stream`, timed by `timer`, wired as `mode` says, with [`DEFAULT_TIMEOUT`] and
    /// [`DEFAULT_QUIET`]. The line settings (8N1 at the drive's baud rate) are the stream's.
    pub fn new(stream: S, timer: T, mode: LoopMode) -> Self {
        Self {
            stream,
            alarm: timer.alarm(),
            timer,
            mode,
            timeout: DEFAULT_TIMEOUT,
            quiet: DEFAULT_QUIET,
            open: false,
        }
    }

    /// Sets how long the drive has to answer (the echo included, in multi-point mode).
    pub fn with_timeout(mut self, timeout: Duration) -> Self {
        self.timeout = timeout;
        self
    }

    /// Sets the silence that closes an exchange that did not end with its answer.
    pub fn with_quiet(mut self, quiet: Duration) -> Self {
        self.quiet = quiet;
        self
    }

    /// The underlying stream.
    pub fn stream_mut(&mut self) -> &mut S {
        &mut self.stream
    }

    /// Gives the stream back.
    pub fn into_stream(self) -> S {
        self.stream
    }

    /// Drops input before a request: what is buffered now, and, after an exchange that did not
    /// end with its answer, everything until the line has been quiet for the quiet time.
    async fn drain(&mut self) -> Result<(), BusError> {
        let mut junk = [0u8; 64];
        for _ in 0..MAX_DRAIN_READS {
            let read = if self.open {
                within(&self.timer, self.quiet, self.stream.read(&mut junk))
                    .await
                    .ok()
            } else {
                ready_now(self.stream.read(&mut junk)).await
            };
            match read {
                None => {
                    self.open = false;
                    return Ok(());
                }
                Some(Ok(0)) => return Err(closed()),
                Some(Ok(_)) => {}
                Some(Err(e)) => return Err(bus_error(&e)),
            }
        }
        Ok(())
    }

    /// Feeds what the stream reads to `exchange` until it has its answer.
    async fn answer(stream: &mut S, exchange: &mut Exchange) -> Result<Answer, AnswerError> {
        let mut chunk = [0u8; TELEGRAM_LEN];
        loop {
            let received = match stream.read(&mut chunk).await {
                Ok(0) => return Err(AnswerError::Bus(closed())),
                Ok(n) => n,
                Err(e) => return Err(AnswerError::Bus(bus_error(&e))),
            };
            if let Some(answer) = exchange
                .receive(&chunk[..received])
                .map_err(AnswerError::Exchange)?
            {
                return Ok(answer);
            }
        }
    }

    /// Writes the whole telegram.
    async fn send(&mut self, telegram: &[u8]) -> Result<(), BusError> {
        embedded_io_async::Write::write_all(&mut self.stream, telegram)
            .await
            .map_err(|e| bus_error(&e))?;
        self.stream.flush().await.map_err(|e| bus_error(&e))
    }
}

/// How waiting for an answer failed.
enum AnswerError {
    Bus(BusError),
    Exchange(super::Rs232Error),
}

impl<S: embedded_io_async::Read + embedded_io_async::Write, T: Timer> AsyncTelegramBus
    for AsyncRs232Client<S, T>
{
    async fn exchange(
        &mut self,
        station: StationId,
        request: &Request,
    ) -> Result<Answer, BusError> {
        let object = request.object();
        let mut exchange = Exchange::new(station, *request, self.mode);
        self.drain().await?;
        // From here until the answer, a dropped future leaves the exchange open.
        self.open = true;
        self.send(exchange.telegram()).await?;
        let waited = within_alarm(
            &mut self.alarm,
            self.timeout,
            Self::answer(&mut self.stream, &mut exchange),
        )
        .await;
        match waited {
            Ok(Ok(answer)) => {
                self.open = false;
                Ok(answer)
            }
            Ok(Err(AnswerError::Bus(error))) => Err(error),
            Ok(Err(AnswerError::Exchange(error))) => Err(error.about(object)),
            Err(_elapsed) => Err(exchange.timed_out().about(object)),
        }
    }
}

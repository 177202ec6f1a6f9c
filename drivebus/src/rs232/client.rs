//! A blocking RS-232 host over any [`ByteStream`], and how to open it on a serial port.
//!
//! The byte channel is the one the Modbus clients use too ([`ByteStream`], [`SerialStream`] in
//! [`crate::stream`]): a serial port, a pty, or a test double.

use core::time::Duration;
use std::time::Instant;

use super::data::{Answer, Request};
use super::exchange::Exchange;
use super::telegram::TELEGRAM_LEN;
use super::{LoopMode, StationId, TelegramBus};
use crate::error::BusError;
use crate::stream::{ByteStream, SerialStream};

/// The drive's factory baud rate (manual line 2173).
pub const DEFAULT_BAUD: u32 = 38_400;

/// Line settings and host behaviour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rs232Config {
    /// Baud rate; 8 data bits, 1 stop bit, no parity are fixed (manual lines 2173–2179).
    pub baud: u32,
    /// How long to wait for the whole answer (and, in multi-point mode, the echo before it).
    pub timeout: Duration,
    /// Point-to-point or multi-point loop wiring.
    pub mode: LoopMode,
}

impl Default for Rs232Config {
    /// 38400 Bd, a 500 ms timeout, point-to-point.
    fn default() -> Self {
        Self {
            baud: DEFAULT_BAUD,
            timeout: Duration::from_millis(500),
            mode: LoopMode::PointToPoint,
        }
    }
}

/// A blocking RS-232 host: one [`Exchange`] at a time over a byte stream.
///
/// Nothing is repeated on its own: a lost answer to a download leaves open whether the drive
/// carried it out, and only the caller knows whether writing again is harmless.
#[derive(Debug)]
pub struct Rs232Client<S> {
    stream: S,
    config: Rs232Config,
}

/// Opens the serial port at `path` with the protocol's line settings: 8N1 at `config.baud`
/// (for a host, or for a simulated drive).
pub fn open_line(path: &str, config: &Rs232Config) -> Result<SerialStream, BusError> {
    SerialStream::open_8_bits(
        path,
        config.baud,
        serialport::Parity::None,
        serialport::StopBits::One,
        config.timeout,
    )
}

impl Rs232Client<SerialStream> {
    /// Opens the serial port at `path` (`/dev/ttyUSB0`, `COM3`) with 8N1 at `config.baud`.
    pub fn open(path: &str, config: Rs232Config) -> Result<Self, BusError> {
        Ok(Self::new(open_line(path, &config)?, config))
    }
}

impl<S: ByteStream> Rs232Client<S> {
    /// A host on `stream`.
    pub fn new(stream: S, config: Rs232Config) -> Self {
        Self { stream, config }
    }

    /// The settings.
    pub fn config(&self) -> &Rs232Config {
        &self.config
    }

    /// The underlying stream.
    pub fn stream_mut(&mut self) -> &mut S {
        &mut self.stream
    }

    /// Gives the stream back.
    pub fn into_stream(self) -> S {
        self.stream
    }
}

impl<S: ByteStream> TelegramBus for Rs232Client<S> {
    fn exchange(&mut self, station: StationId, request: &Request) -> Result<Answer, BusError> {
        let object = request.object();
        let mut exchange = Exchange::new(station, *request, self.config.mode);
        // Late answers to an earlier request and line noise must not pass for this answer.
        self.stream.discard_input()?;
        self.stream.send(exchange.telegram())?;
        let deadline = Instant::now() + self.config.timeout;
        let mut chunk = [0u8; TELEGRAM_LEN];
        loop {
            let received = self.stream.receive(&mut chunk, deadline)?;
            if received == 0 {
                return Err(exchange.timed_out().about(object));
            }
            if let Some(answer) = exchange
                .receive(&chunk[..received])
                .map_err(|error| error.about(object))?
            {
                return Ok(answer);
            }
        }
    }
}

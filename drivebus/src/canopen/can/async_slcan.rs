//! SLCAN adapters over an async byte stream (`embedded-io-async`): the async twin of
//! [`SlcanBus`](super::slcan::SlcanBus), decoding with the same sans-I/O codec.

use core::time::Duration;

use super::async_line::LineWriter;
use super::slcan::{encode_frame, Bitrate};
use super::slcan_decoder::{Answer, SlcanDecoder};
use super::{AsyncCanBus, CanEvent, OpenError};
use crate::asynch::io_error::{bus_error, closed};
use crate::asynch::{within, Timer};
use crate::canopen::frame::CanFrame;
use crate::error::BusError;

/// An [`AsyncCanBus`] over an SLCAN adapter reached through an async byte stream (a serial
/// port, TCP). Receiving is cancel-safe when the stream's `read` is (tokio's streams are).
#[derive(Debug)]
pub struct AsyncSlcanBus<S> {
    stream: S,
    decoder: SlcanDecoder,
    writer: LineWriter,
}

impl<S: embedded_io_async::Read + embedded_io_async::Write> AsyncSlcanBus<S> {
    /// Wraps a stream.
    pub fn new(stream: S) -> Self {
        Self {
            stream,
            decoder: SlcanDecoder::default(),
            writer: LineWriter::default(),
        }
    }

    async fn command(&mut self, command: &[u8]) -> Result<(), BusError> {
        self.writer
            .send(&mut self.stream, |line| line.extend_from_slice(command))
            .await
    }

    /// Closes the channel, sets the bit rate and opens it (`C`, `Sn`, `O`) without waiting for
    /// answers, as [`SlcanBus::open`](super::slcan::SlcanBus::open) does.
    pub async fn open(&mut self, bitrate: Bitrate) -> Result<(), BusError> {
        self.command(b"C\r").await?;
        self.command(&[b'S', b'0' + bitrate.code(), b'\r']).await?;
        self.command(b"O\r").await
    }

    /// Closes the channel, sets the bit rate and opens it, checking that the adapter answers
    /// `Sn` and `O` within `answer_timeout` of `timer`'s time each, as
    /// [`SlcanBus::start`](super::slcan::SlcanBus::start) does.
    pub async fn start(
        &mut self,
        bitrate: Bitrate,
        timer: &impl Timer,
        answer_timeout: Duration,
    ) -> Result<(), OpenError> {
        const RATES: [&str; 9] = ["S0", "S1", "S2", "S3", "S4", "S5", "S6", "S7", "S8"];
        self.command(b"C\r").await.map_err(open_error)?;
        // An adapter in an unknown state: its answer to C is awaited but not judged.
        let _ = within(timer, answer_timeout, self.answer()).await;
        let rate = RATES[usize::from(bitrate.code())];
        for (command, name) in [
            (&[b'S', b'0' + bitrate.code(), b'\r'][..], rate),
            (b"O\r", "O"),
        ] {
            self.command(command).await.map_err(open_error)?;
            match within(timer, answer_timeout, self.answer()).await {
                Ok(Ok(Answer::Accepted)) => {}
                Ok(Ok(Answer::Refused)) => return Err(OpenError::Refused { command: name }),
                Ok(Err(e)) => return Err(open_error(e)),
                Err(_) => return Err(OpenError::NoAnswer { command: name }),
            }
        }
        Ok(())
    }

    /// The next answer to a command; frame lines before it stay buffered.
    async fn answer(&mut self) -> Result<Answer, BusError> {
        loop {
            if let Some(answer) = self.decoder.take_answer() {
                return Ok(answer);
            }
            self.fill().await?;
        }
    }

    /// Closes the channel (`C`).
    pub async fn close(&mut self) -> Result<(), BusError> {
        self.command(b"C\r").await
    }

    /// Commands and frames the adapter refused (BEL answers) so far.
    pub fn refused_commands(&self) -> usize {
        self.decoder.refused()
    }

    /// The stream.
    pub fn stream_mut(&mut self) -> &mut S {
        &mut self.stream
    }

    /// Reads more bytes into the decoder. Cancel-safe: bytes are handed over in the poll that
    /// read them.
    async fn fill(&mut self) -> Result<(), BusError> {
        let mut chunk = [0u8; 256];
        match self.stream.read(&mut chunk).await {
            Ok(0) => Err(closed()),
            Ok(n) => {
                self.decoder.push(&chunk[..n]);
                Ok(())
            }
            Err(e) => Err(bus_error(&e)),
        }
    }

    /// The next frame or report (status answers, refusals, noise), as
    /// [`CanBus::recv_event`](super::CanBus::recv_event) reports them.
    pub async fn recv_event(&mut self) -> Result<CanEvent, BusError> {
        loop {
            if let Some(event) = self.decoder.next_event() {
                return event;
            }
            self.fill().await?;
        }
    }
}

fn open_error(error: BusError) -> OpenError {
    match error {
        BusError::Io(std::io::ErrorKind::PermissionDenied) => OpenError::PermissionDenied {
            what: "the SLCAN adapter".into(),
        },
        BusError::Io(kind) => OpenError::Io(kind),
        _ => OpenError::Io(std::io::ErrorKind::Other),
    }
}

impl<S: embedded_io_async::Read + embedded_io_async::Write> AsyncCanBus for AsyncSlcanBus<S> {
    async fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.writer
            .send(&mut self.stream, |line| encode_frame(frame, line))
            .await
    }

    /// The next frame; noise, malformed lines, status reports and refusals are skipped
    /// ([`AsyncSlcanBus::recv_event`] reports them).
    async fn recv(&mut self) -> Result<CanFrame, BusError> {
        loop {
            if let CanEvent::Frame { frame, .. } = self.recv_event().await? {
                return Ok(frame);
            }
        }
    }
}

//! candump text over async byte streams: the async twin of
//! [`CandumpBus`](super::candump::CandumpBus), parsing with the same line parser.

use std::vec::Vec;

use super::async_line::LineWriter;
use super::candump::{format_frame, parse_line, Record, MAX_LINE};
use super::AsyncCanBus;
use crate::asynch::io_error::{bus_error, closed};
use crate::canopen::frame::CanFrame;
use crate::error::BusError;

/// An [`AsyncCanBus`] over candump text: frames are written as compact lines to `W` and read
/// from `R` (a relay's stdio, a pipe, a log being replayed). Lines that do not parse are
/// skipped and counted: a relay may print other text. Receiving is cancel-safe when `R`'s
/// `read` is.
#[derive(Debug)]
pub struct AsyncCandumpBus<R, W> {
    reader: R,
    writer: W,
    pending: Vec<u8>,
    /// A line over [`MAX_LINE`] is being dropped up to its newline.
    skipping: bool,
    malformed: usize,
    line: LineWriter,
}

impl<R: embedded_io_async::Read, W: embedded_io_async::Write> AsyncCandumpBus<R, W> {
    /// Reads frames from `reader` and writes frames to `writer`.
    pub fn new(reader: R, writer: W) -> Self {
        Self {
            reader,
            writer,
            pending: Vec::with_capacity(MAX_LINE),
            skipping: false,
            malformed: 0,
            line: LineWriter::default(),
        }
    }

    /// Lines skipped because they were not frames (or were longer than [`MAX_LINE`]).
    pub fn malformed_lines(&self) -> usize {
        self.malformed
    }

    /// The writer.
    pub fn writer_mut(&mut self) -> &mut W {
        &mut self.writer
    }

    /// The next whole record in the buffer, skipping blank lines, comments and malformed lines.
    fn next_in_buffer(&mut self) -> Option<Record> {
        while let Some(end) = self.pending.iter().position(|&b| b == b'\n') {
            let line: Vec<u8> = self.pending.drain(..=end).collect();
            if core::mem::take(&mut self.skipping) {
                continue;
            }
            match parse_line(&line) {
                Ok(Some(record)) => return Some(record),
                Ok(None) => {}
                Err(_) => self.malformed += 1,
            }
        }
        if self.pending.len() > MAX_LINE {
            // No newline in sight: the line is dropped, up to the newline that ends it.
            self.pending.clear();
            if !self.skipping {
                self.malformed += 1;
            }
            self.skipping = true;
        }
        None
    }

    /// The next frame with its log timestamp, if any. At the end of the stream: an error
    /// ([`BusError::Io`], `UnexpectedEof`); a last line without newline still counts.
    pub async fn recv_record(&mut self) -> Result<Record, BusError> {
        let mut chunk = [0u8; 256];
        loop {
            if let Some(record) = self.next_in_buffer() {
                return Ok(record);
            }
            match self.reader.read(&mut chunk).await {
                Ok(0) if !self.pending.is_empty() && !self.skipping => {
                    self.pending.push(b'\n');
                }
                Ok(0) => return Err(closed()),
                Ok(n) => self.pending.extend_from_slice(&chunk[..n]),
                Err(e) => return Err(bus_error(&e)),
            }
        }
    }
}

impl<R: embedded_io_async::Read, W: embedded_io_async::Write> AsyncCanBus
    for AsyncCandumpBus<R, W>
{
    async fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.line
            .send(&mut self.writer, |line| {
                format_frame(frame, line);
                line.push(b'\n');
            })
            .await
    }

    async fn recv(&mut self) -> Result<CanFrame, BusError> {
        Ok(self.recv_record().await?.frame)
    }
}

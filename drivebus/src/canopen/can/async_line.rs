//! A cancel-safe line writer for the async text interfaces (SLCAN, candump).

use std::vec::Vec;

use crate::asynch::io_error::{bus_error, closed};
use crate::error::BusError;

/// The line being written and how much of it went out. A send whose future was dropped
/// mid-line is finished before the next line starts, so the peer never sees a torn line.
#[derive(Debug, Default)]
pub(crate) struct LineWriter {
    line: Vec<u8>,
    sent: usize,
}

impl LineWriter {
    /// Writes what is left of the current line, then flushes.
    pub(crate) async fn finish<W: embedded_io_async::Write>(
        &mut self,
        writer: &mut W,
    ) -> Result<(), BusError> {
        while self.sent < self.line.len() {
            match writer.write(&self.line[self.sent..]).await {
                Ok(0) => return Err(closed()),
                Ok(n) => self.sent += n,
                Err(e) => return Err(bus_error(&e)),
            }
        }
        writer.flush().await.map_err(|e| bus_error(&e))
    }

    /// Finishes the previous line, then writes the line `encode` appends to an empty buffer.
    pub(crate) async fn send<W: embedded_io_async::Write>(
        &mut self,
        writer: &mut W,
        encode: impl FnOnce(&mut Vec<u8>),
    ) -> Result<(), BusError> {
        self.finish(writer).await?;
        self.line.clear();
        self.sent = 0;
        encode(&mut self.line);
        self.finish(writer).await
    }
}

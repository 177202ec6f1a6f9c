//! A serial port as a [`ByteStream`] (`serialport` crate), whatever protocol runs on it.

use std::boxed::Box;
use std::io::{ErrorKind, Read, Write};
use std::time::{Duration, Instant};

use serialport::{ClearBuffer, DataBits, FlowControl, Parity, SerialPort, StopBits};

use super::{io_error, ByteStream};
use crate::error::BusError;

/// The line settings of `path`: `baud`, 8 data bits, `parity`, `stop_bits`, no flow control.
pub(crate) fn settings_8_bits(
    path: &str,
    baud: u32,
    parity: Parity,
    stop_bits: StopBits,
) -> serialport::SerialPortBuilder {
    serialport::new(path, baud)
        .data_bits(DataBits::Eight)
        .parity(parity)
        .stop_bits(stop_bits)
        .flow_control(FlowControl::None)
}

/// The bus error of a failure to open or set up a port.
pub(crate) fn serial_error(error: serialport::Error) -> BusError {
    BusError::Io(match error.kind {
        serialport::ErrorKind::Io(kind) => kind,
        serialport::ErrorKind::NoDevice => ErrorKind::NotFound,
        serialport::ErrorKind::InvalidInput => ErrorKind::InvalidInput,
        serialport::ErrorKind::Unknown => ErrorKind::Other,
    })
}

/// A serial port as a [`ByteStream`].
pub struct SerialStream {
    port: Box<dyn SerialPort>,
}

impl core::fmt::Debug for SerialStream {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SerialStream")
            .field("port", &self.port.name())
            .finish()
    }
}

impl SerialStream {
    /// Opens `path` (`/dev/ttyUSB0`, `COM3`) at `baud` with 8 data bits, `parity`, `stop_bits`
    /// and no flow control; `timeout` is the port's initial read timeout.
    pub fn open_8_bits(
        path: &str,
        baud: u32,
        parity: Parity,
        stop_bits: StopBits,
        timeout: Duration,
    ) -> Result<Self, BusError> {
        let port = settings_8_bits(path, baud, parity, stop_bits)
            .timeout(timeout)
            .open()
            .map_err(serial_error)?;
        Ok(Self { port })
    }

    /// Wraps a port opened elsewhere.
    pub fn from_port(port: Box<dyn SerialPort>) -> Self {
        Self { port }
    }
}

/// Shortest read timeout handed to the port, so a nearly expired deadline still polls once.
const MIN_POLL: Duration = Duration::from_millis(1);

impl ByteStream for SerialStream {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        self.port.write_all(bytes).map_err(io_error)?;
        self.port.flush().map_err(io_error)
    }

    fn receive(&mut self, buf: &mut [u8], deadline: Instant) -> Result<usize, BusError> {
        loop {
            let Some(left) = deadline.checked_duration_since(Instant::now()) else {
                return Ok(0);
            };
            self.port
                .set_timeout(left.max(MIN_POLL))
                .map_err(serial_error)?;
            match self.port.read(buf) {
                Ok(0) => std::thread::sleep(MIN_POLL),
                Ok(n) => return Ok(n),
                Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock) => {}
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => return Err(io_error(e)),
            }
        }
    }

    fn discard_input(&mut self) -> Result<(), BusError> {
        self.port.clear(ClearBuffer::Input).map_err(serial_error)
    }
}

//! Byte streams under the serial-line protocols: the channel a Modbus client and a Kinco RS-232
//! host both read and write.
//!
//! * [`ByteStream`] — send, receive with a deadline, drop stale input, reconnect: a serial port,
//!   a TCP connection, a pty or a test double.
//! * `SerialStream` (feature `serial`, pulled in by `modbus` and by `rs232`) — a serial port
//!   ([`serialport`](https://docs.rs/serialport)) as a byte stream.
//! * `TokioSerialStream` (features `tokio` and `serial`, Unix) — a serial port as an
//!   `embedded-io-async` stream for the async API.
//!
//! Neither protocol depends on the other: `--features rs232` builds without Modbus.

#[cfg(feature = "serial")]
mod serial;
#[cfg(all(feature = "tokio", feature = "serial", unix))]
mod tokio_serial;

use std::time::Instant;

use crate::error::BusError;

#[cfg(feature = "serial")]
pub use serial::SerialStream;
#[cfg(all(feature = "tokio", feature = "serial", unix))]
pub use tokio_serial::TokioSerialStream;

/// The byte channel under a client: a serial port, a TCP connection, or a test double.
pub trait ByteStream {
    /// Sends all of `bytes`.
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError>;
    /// Waits until some bytes arrived or `deadline` passed; returns how many were stored in `buf`
    /// (0: the deadline passed).
    fn receive(&mut self, buf: &mut [u8], deadline: Instant) -> Result<usize, BusError>;
    /// Drops input that arrived but was not read: late answers and line noise.
    fn discard_input(&mut self) -> Result<(), BusError>;
    /// Re-establishes the channel after an I/O failure (TCP reconnects). Default: nothing to do.
    fn reconnect(&mut self) -> Result<(), BusError> {
        Ok(())
    }
}

impl<S: ByteStream + ?Sized> ByteStream for &mut S {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        (**self).send(bytes)
    }
    fn receive(&mut self, buf: &mut [u8], deadline: Instant) -> Result<usize, BusError> {
        (**self).receive(buf, deadline)
    }
    fn discard_input(&mut self) -> Result<(), BusError> {
        (**self).discard_input()
    }
    fn reconnect(&mut self) -> Result<(), BusError> {
        (**self).reconnect()
    }
}

/// Maps an I/O error to the bus error that carries its kind.
#[cfg(feature = "serial")]
pub(crate) fn io_error(error: std::io::Error) -> BusError {
    BusError::Io(error.kind())
}

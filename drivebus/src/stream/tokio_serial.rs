//! A serial port as a tokio-driven `embedded-io-async` byte stream (Unix): the port is opened
//! and configured by `serialport`, then read and written without blocking through tokio's
//! reactor.

use std::io;
use std::os::fd::{AsRawFd, RawFd};

use serialport::{Parity, StopBits, TTYPort};
use tokio::io::unix::AsyncFd;
use tokio::io::Interest;

use super::serial::{serial_error, settings_8_bits};

use crate::error::BusError;

/// A serial port for the async API (feature `tokio`, Unix): `embedded-io-async` `Read + Write`.
/// Reads and writes are cancel-safe: a dropped future has moved no byte.
#[derive(Debug)]
pub struct TokioSerialStream {
    port: AsyncFd<TTYPort>,
}

impl TokioSerialStream {
    /// Opens `path` at `baud`, 8N1, no flow control: the SLCAN adapters' and the Kinco RS-232
    /// line's settings.
    ///
    /// # Panics
    /// Outside a tokio runtime with I/O enabled.
    pub fn open_8n1(path: &str, baud: u32) -> Result<Self, BusError> {
        Self::open_8_bits(path, baud, Parity::None, StopBits::One)
    }

    /// Opens `path` (`/dev/ttyUSB0`, a pty) at `baud` with 8 data bits, `parity`, `stop_bits`
    /// and no flow control.
    ///
    /// # Panics
    /// Outside a tokio runtime with I/O enabled (tokio's `AsyncFd` registration does).
    pub fn open_8_bits(
        path: &str,
        baud: u32,
        parity: Parity,
        stop_bits: StopBits,
    ) -> Result<Self, BusError> {
        let port = settings_8_bits(path, baud, parity, stop_bits)
            .open_native()
            .map_err(serial_error)?;
        set_nonblocking(port.as_raw_fd()).map_err(|e| BusError::Io(e.kind()))?;
        // SAFETY: the port owns its descriptor until it is dropped, which only the `AsyncFd`
        // holding it does, and always answers `as_raw_fd` with that descriptor.
        let port = unsafe { AsyncFd::register(port) }
            .map_err(|e| BusError::Io(e.into_parts().1.kind()))?;
        Ok(Self { port })
    }
}

fn set_nonblocking(fd: RawFd) -> io::Result<()> {
    // SAFETY: fcntl on a descriptor this process owns, with integer arguments only.
    let flags = unsafe { libc::fcntl(fd, libc::F_GETFL) };
    if flags < 0 {
        return Err(io::Error::last_os_error());
    }
    // SAFETY: as above.
    if unsafe { libc::fcntl(fd, libc::F_SETFL, flags | libc::O_NONBLOCK) } < 0 {
        return Err(io::Error::last_os_error());
    }
    Ok(())
}

/// The result of a read(2) or write(2): bytes moved, or the error (`WouldBlock` included).
fn outcome(result: isize) -> io::Result<usize> {
    usize::try_from(result).map_err(|_| io::Error::last_os_error())
}

impl embedded_io_async::ErrorType for TokioSerialStream {
    type Error = io::Error;
}

impl TokioSerialStream {
    /// Runs `syscall` on the descriptor once it is ready for `interest`, again after each
    /// `WouldBlock`. `serialport`'s own `read` polls with a timeout: the descriptor is used
    /// directly.
    async fn when_ready(
        &self,
        interest: Interest,
        mut syscall: impl FnMut(RawFd) -> isize,
    ) -> io::Result<usize> {
        self.port
            .async_io(interest, |port| outcome(syscall(port.as_raw_fd())))
            .await
    }
}

impl embedded_io_async::Read for TokioSerialStream {
    async fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        if buf.is_empty() {
            return Ok(0);
        }
        // SAFETY: `buf` is valid for `buf.len()` bytes of writes.
        let read = |fd| unsafe { libc::read(fd, buf.as_mut_ptr().cast(), buf.len()) };
        self.when_ready(Interest::READABLE, read).await
    }
}

impl embedded_io_async::Write for TokioSerialStream {
    async fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if buf.is_empty() {
            return Ok(0);
        }
        // SAFETY: `buf` is valid for `buf.len()` bytes of reads.
        let write = |fd| unsafe { libc::write(fd, buf.as_ptr().cast(), buf.len()) };
        self.when_ready(Interest::WRITABLE, write).await
    }

    async fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

//! The async CAN interfaces on tokio's streams (feature `tokio`): SLCAN over TCP and over a
//! serial port, candump over a child process's stdio. Each is an `embedded-io-async` stream
//! (`embedded-io-adapters`' `FromTokio`) under the runtime-agnostic bus.

use embedded_io_adapters::tokio_1::FromTokio;
use tokio::net::{TcpStream, ToSocketAddrs};
use tokio::process::{Child, ChildStdin, ChildStdout};

use super::async_candump::AsyncCandumpBus;
use super::async_slcan::AsyncSlcanBus;
use super::candump::piped;
use crate::error::BusError;

/// A tokio stream as an `embedded-io-async` one.
pub type TokioIo<T> = FromTokio<T>;

impl AsyncSlcanBus<TokioIo<TcpStream>> {
    /// Connects to an SLCAN-over-TCP adapter or gateway; call
    /// [`start`](AsyncSlcanBus::start) or [`open`](AsyncSlcanBus::open) next.
    pub async fn connect(address: impl ToSocketAddrs) -> Result<Self, BusError> {
        let stream = TcpStream::connect(address)
            .await
            .map_err(|e| BusError::Io(e.kind()))?;
        stream
            .set_nodelay(true)
            .map_err(|e| BusError::Io(e.kind()))?;
        Ok(Self::new(FromTokio::new(stream)))
    }
}

#[cfg(all(feature = "serial", unix))]
impl AsyncSlcanBus<crate::stream::TokioSerialStream> {
    /// Opens a serial SLCAN adapter (`/dev/ttyACM0`) at `baud`, 8N1, no flow control (see
    /// [`SlcanBus::serial`](super::slcan::SlcanBus::serial)); call
    /// [`start`](AsyncSlcanBus::start) next.
    pub fn serial(path: &str, baud: u32) -> Result<Self, BusError> {
        Ok(Self::new(crate::stream::TokioSerialStream::open_8n1(
            path, baud,
        )?))
    }
}

impl AsyncCandumpBus<TokioIo<ChildStdout>, TokioIo<ChildStdin>> {
    /// A bus over a tokio child process's stdio (spawned with piped stdin and stdout), e.g. a
    /// relay to another CAN stack. The child stays owned by the caller, who must stop it.
    pub fn from_child(child: &mut Child) -> Result<Self, BusError> {
        let (stdin, stdout) = piped(child.stdin.take(), child.stdout.take())?;
        Ok(Self::new(FromTokio::new(stdout), FromTokio::new(stdin)))
    }
}

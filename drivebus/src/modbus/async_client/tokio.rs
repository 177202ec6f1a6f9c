//! tokio adapters for the async Modbus clients (feature `tokio`): a TCP connection as an
//! `embedded-io-async` stream (through `embedded-io-adapters`), timed by [`TokioTimer`].
//!
//! A serial port: open it with any crate that gives a tokio `AsyncRead + AsyncWrite`
//! (`tokio-serial`'s `SerialStream`) and wrap it in [`FromTokio`] for
//! [`AsyncClient::rtu`](super::AsyncClient::rtu); drivebus does not depend on one.

use tokio::net::{TcpStream, ToSocketAddrs};

pub use embedded_io_adapters::tokio_1::FromTokio;

use super::{AsyncClient, AsyncClientConfig, AsyncTcpClient};
use crate::asynch::{within, TokioTimer};
use crate::error::BusError;

/// A TCP connection as the async clients' stream.
pub type TokioTcp = FromTokio<TcpStream>;

/// Connects to `addr` within `config.timeout`, without Nagle's delay (requests are single
/// small writes).
pub async fn connect(
    addr: impl ToSocketAddrs,
    config: &AsyncClientConfig,
) -> Result<TokioTcp, BusError> {
    let stream = within(&TokioTimer, config.timeout, TcpStream::connect(addr))
        .await
        .map_err(|_| BusError::Timeout)?
        .map_err(|e| BusError::Io(e.kind()))?;
    stream
        .set_nodelay(true)
        .map_err(|e| BusError::Io(e.kind()))?;
    Ok(FromTokio::new(stream))
}

impl AsyncTcpClient<TokioTcp, TokioTimer> {
    /// Connects to a Modbus TCP server (`"192.168.0.10:502"`) on tokio.
    pub async fn connect(
        addr: impl ToSocketAddrs,
        config: AsyncClientConfig,
    ) -> Result<Self, BusError> {
        Ok(AsyncClient::tcp(
            connect(addr, &config).await?,
            TokioTimer,
            config,
        ))
    }
}

#[cfg(feature = "modbus-core")]
impl super::AsyncRtuClient<TokioTcp, TokioTimer> {
    /// Connects to a serial gateway (`"192.168.0.20:4001"`) that forwards RTU frames to the
    /// serial line (RTU over TCP) on tokio.
    pub async fn connect(
        addr: impl ToSocketAddrs,
        config: AsyncClientConfig,
    ) -> Result<Self, BusError> {
        Ok(AsyncClient::rtu(
            connect(addr, &config).await?,
            TokioTimer,
            config,
        ))
    }
}

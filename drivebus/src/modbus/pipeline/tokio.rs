//! The pipeline on tokio (feature `tokio`): a TCP connection split into its halves.

use tokio::net::tcp::{OwnedReadHalf, OwnedWriteHalf};
use tokio::net::ToSocketAddrs;

use super::TcpPipeline;
use crate::asynch::TokioTimer;
use crate::error::BusError;
use crate::modbus::async_client::tokio::{connect, FromTokio};
use crate::modbus::async_client::AsyncClientConfig;

/// A pipeline over a tokio TCP connection.
pub type TokioPipeline =
    TcpPipeline<FromTokio<OwnedReadHalf>, FromTokio<OwnedWriteHalf>, TokioTimer>;

impl TokioPipeline {
    /// Connects to a Modbus TCP server (`"192.168.0.10:502"`) on tokio; `config.timeout` is
    /// the connect timeout and each request's (its retry and pacing settings do not apply).
    pub async fn connect(
        addr: impl ToSocketAddrs,
        config: &AsyncClientConfig,
    ) -> Result<Self, BusError> {
        let (reader, writer) = connect(addr, config).await?.into_inner().into_split();
        Ok(Self::new(
            FromTokio::new(reader),
            FromTokio::new(writer),
            TokioTimer,
            config.timeout,
        ))
    }
}

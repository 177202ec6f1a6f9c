//! Modbus RTU frames over TCP, as serial-to-Ethernet gateways in transparent mode carry them.
//!
//! There is no transaction id, so stale answers are kept out by draining the socket before every
//! request and by checking each answer against the request; the gateway owns the serial timing.

use std::net::ToSocketAddrs;

use super::tcp::{NetStream, TcpConfig};
use super::Client;
use crate::error::BusError;
use crate::modbus::rtu::RtuFraming;

/// Modbus RTU framing over a TCP connection to a serial gateway.
pub type RtuOverTcpClient = Client<NetStream, RtuFraming>;

impl RtuOverTcpClient {
    /// Connects to a gateway (`"192.168.0.20:4001"`) that forwards RTU frames to the serial line.
    pub fn connect(addr: impl ToSocketAddrs, config: &TcpConfig) -> Result<Self, BusError> {
        let stream = NetStream::connect(addr, config.connect_timeout)?;
        Ok(Client::new(stream, RtuFraming, config.client_config()))
    }
}

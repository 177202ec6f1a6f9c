//! Modbus TCP: MBAP frames over a TCP connection, reconnecting after failures.

use std::io::{ErrorKind, Read, Write};
use std::net::{SocketAddr, TcpStream, ToSocketAddrs};
use std::time::{Duration, Instant};

use super::{io_error, ByteStream, Client, ClientConfig};
use crate::error::BusError;
use crate::modbus::retry::RetryPolicy;
use crate::modbus::tcp::TcpFraming;

/// Connection and client settings for Modbus TCP and RTU-over-TCP.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TcpConfig {
    /// How long to wait for each answer.
    pub timeout: Duration,
    /// How long to wait for the connection to be established.
    pub connect_timeout: Duration,
    /// Least pause between an answer and the next request (for gateways that need one).
    pub turnaround: Duration,
    /// Which failed requests are repeated.
    pub retry: RetryPolicy,
    /// How many reads of a batch may await their answers at once: above 1, Modbus TCP sends
    /// them together (see [`ClientConfig::max_in_flight`]); RTU over TCP ignores it.
    pub max_in_flight: usize,
}

impl Default for TcpConfig {
    fn default() -> Self {
        Self {
            timeout: Duration::from_secs(1),
            connect_timeout: Duration::from_secs(3),
            turnaround: Duration::ZERO,
            retry: RetryPolicy::reads(2),
            max_in_flight: 1,
        }
    }
}

impl TcpConfig {
    /// The client settings.
    pub fn client_config(&self) -> ClientConfig {
        ClientConfig {
            timeout: self.timeout,
            retry: self.retry,
            idle_gap: self.turnaround,
            max_in_flight: self.max_in_flight,
        }
    }
}

/// A TCP connection as a [`ByteStream`]; reconnects to the same peer on request.
#[derive(Debug)]
pub struct NetStream {
    stream: TcpStream,
    peer: SocketAddr,
    connect_timeout: Duration,
    /// The socket's current read timeout, to skip a syscall per read when it is still fitting.
    read_timeout: Duration,
}

fn open(peer: &SocketAddr, connect_timeout: Duration) -> Result<TcpStream, BusError> {
    let stream = TcpStream::connect_timeout(peer, connect_timeout).map_err(io_error)?;
    // Requests are single small writes: Nagle would only add latency.
    stream.set_nodelay(true).map_err(io_error)?;
    Ok(stream)
}

impl NetStream {
    /// Connects to the first address `addr` resolves to.
    pub fn connect(addr: impl ToSocketAddrs, connect_timeout: Duration) -> Result<Self, BusError> {
        let peer = addr
            .to_socket_addrs()
            .map_err(io_error)?
            .next()
            .ok_or(BusError::Io(ErrorKind::AddrNotAvailable))?;
        Ok(Self {
            stream: open(&peer, connect_timeout)?,
            peer,
            connect_timeout,
            read_timeout: Duration::ZERO,
        })
    }

    /// The peer's address.
    pub fn peer(&self) -> SocketAddr {
        self.peer
    }
}

/// Shortest read timeout handed to the socket (zero would mean "block forever").
const MIN_POLL: Duration = Duration::from_millis(1);

impl ByteStream for NetStream {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        self.stream.write_all(bytes).map_err(io_error)
    }

    fn receive(&mut self, buf: &mut [u8], deadline: Instant) -> Result<usize, BusError> {
        loop {
            let Some(left) = deadline.checked_duration_since(Instant::now()) else {
                return Ok(0);
            };
            // A read may end before the deadline (the loop re-checks) but never after it; with
            // headroom below `left`, consecutive requests reuse the timeout without a syscall.
            if self.read_timeout > left || self.read_timeout < left / 2 {
                self.read_timeout = (left * 3 / 4).max(MIN_POLL);
                self.stream
                    .set_read_timeout(Some(self.read_timeout))
                    .map_err(io_error)?;
            }
            match self.stream.read(buf) {
                Ok(0) => return Err(BusError::Io(ErrorKind::ConnectionAborted)),
                Ok(n) => return Ok(n),
                Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock) => {}
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => return Err(io_error(e)),
            }
        }
    }

    /// Drops what is waiting, up to `MAX_DISCARD` bytes: a peer that never stops sending
    /// cannot hold the client here (what is left is dropped by the framing, whose transaction
    /// ids it cannot match, within the exchange's timeout).
    fn discard_input(&mut self) -> Result<(), BusError> {
        self.stream.set_nonblocking(true).map_err(io_error)?;
        let mut scratch = [0u8; 4096];
        let mut dropped = 0;
        let closed = loop {
            if dropped >= MAX_DISCARD {
                break false;
            }
            match self.stream.read(&mut scratch) {
                Ok(0) => break true,
                Ok(n) => dropped += n,
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) if e.kind() == ErrorKind::WouldBlock => break false,
                Err(_) => break true,
            }
        };
        if closed {
            // Nothing has been sent yet, so reconnecting here is safe even for writes.
            return self.reconnect();
        }
        self.stream.set_nonblocking(false).map_err(io_error)
    }

    fn reconnect(&mut self) -> Result<(), BusError> {
        self.stream = open(&self.peer, self.connect_timeout)?;
        self.read_timeout = Duration::ZERO;
        Ok(())
    }
}

/// Most bytes one flush before a request drops (see `NetStream::discard_input`).
const MAX_DISCARD: usize = 64 * 1024;

/// Modbus TCP (MBAP framing) over a TCP connection.
pub type ModbusTcpClient = Client<NetStream, TcpFraming>;

impl ModbusTcpClient {
    /// Connects to a Modbus TCP server (`"192.168.0.10:502"`).
    pub fn connect(addr: impl ToSocketAddrs, config: &TcpConfig) -> Result<Self, BusError> {
        let stream = NetStream::connect(addr, config.connect_timeout)?;
        Ok(Client::new(
            stream,
            TcpFraming::default(),
            config.client_config(),
        ))
    }
}

#[cfg(test)]
mod tests {
    use std::io::{Read, Write};
    use std::net::{TcpListener, TcpStream};
    use std::sync::mpsc;
    use std::vec;
    use std::vec::Vec;

    use super::*;
    use crate::modbus::{RegisterBus, Table, UnitId};

    /// Reads one MBAP ADU; `None` at the end of the connection.
    fn next_adu(stream: &mut TcpStream) -> Option<Vec<u8>> {
        let mut adu = vec![0u8; 6];
        stream.read_exact(&mut adu).ok()?;
        let length = usize::from(u16::from_be_bytes([adu[4], adu[5]]));
        adu.resize(6 + length, 0);
        stream.read_exact(&mut adu[6..]).ok()?;
        Some(adu)
    }

    #[test]
    fn a_connection_the_server_closed_while_idle_is_reopened_before_a_write_is_sent() {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let addr = listener.local_addr().unwrap();
        let (closed_tx, closed_rx) = mpsc::channel();
        let server = std::thread::spawn(move || {
            // First connection: answer one read of one register, then close it (an idle timeout).
            let (mut first, _) = listener.accept().unwrap();
            let read = next_adu(&mut first).unwrap();
            let mut answer = read[..4].to_vec();
            answer.extend_from_slice(&[0, 5, read[6], 0x03, 2, 0x12, 0x34]);
            first.write_all(&answer).unwrap();
            drop(first);
            closed_tx.send(()).unwrap();
            // Second connection: echo writes (FC 0x06 answers with its request) and count them.
            let (mut second, _) = listener.accept().unwrap();
            let mut writes = 0;
            while let Some(write) = next_adu(&mut second) {
                writes += 1;
                second.write_all(&write).unwrap();
            }
            writes
        });
        let mut client = ModbusTcpClient::connect(addr, &TcpConfig::default()).unwrap();
        let mut value = [0u16];
        client
            .read_registers(UnitId(1), Table::Holding, 0, &mut value)
            .unwrap();
        assert_eq!(value, [0x1234]);
        closed_rx.recv().unwrap();
        // Not idempotent, so never repeated: it must go out once, on a working connection.
        client.write_register(UnitId(1), 5, 77).unwrap();
        drop(client);
        assert_eq!(server.join().unwrap(), 1);
    }
}

//! Modbus TCP: a listener on a loopback (or any) address, one thread per connection, serving one
//! drive or, as a gateway, several drives by unit id ([`Units`]).

use std::io::{ErrorKind, Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream, ToSocketAddrs};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;

use drivebus::modbus::pdu::MAX_PDU;
use drivebus::modbus::tcp::{Header, HEADER_LEN};
use drivebus::modbus::UnitId;

use super::Units;
use crate::Simulator;

/// How often idle connections look at the stop flag.
const POLL: Duration = Duration::from_millis(100);

/// Unit id a Modbus TCP client sends when it does not address a unit behind a gateway.
const TCP_ANY_UNIT: u8 = 0xFF;

/// Unit id 0, a broadcast on a serial line; a Modbus TCP server ignores it.
const BROADCAST: u8 = 0;

/// A running Modbus TCP server; stops when dropped.
#[derive(Debug)]
pub struct TcpServer {
    addr: SocketAddr,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl TcpServer {
    /// Listens on `addr` (port 0: any free port) for requests to `unit` (and 0xFF).
    pub fn start(sim: Simulator, addr: impl ToSocketAddrs, unit: UnitId) -> std::io::Result<Self> {
        Self::gateway(Units::one(sim, unit), addr)
    }

    /// Listens on `addr` (port 0: any free port) for requests to any of `units`, as a gateway
    /// in front of several drives; 0xFF reaches the first unit, other ids get no answer.
    pub fn gateway(units: Units, addr: impl ToSocketAddrs) -> std::io::Result<Self> {
        let listener = TcpListener::bind(addr)?;
        let addr = listener.local_addr()?;
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let thread = std::thread::spawn(move || {
            for stream in listener.incoming() {
                if flag.load(Ordering::Relaxed) {
                    break;
                }
                let Ok(stream) = stream else { continue };
                let (units, flag) = (units.clone(), Arc::clone(&flag));
                std::thread::spawn(move || serve(stream, &units, &flag));
            }
        });
        Ok(Self {
            addr,
            stop,
            thread: Some(thread),
        })
    }

    /// The address it listens on (with the real port).
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// Blocks until the server stops (it runs until dropped elsewhere or the process ends).
    pub fn join(mut self) {
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

impl Drop for TcpServer {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        // Wakes the accept loop so it sees the flag.
        let _ = TcpStream::connect_timeout(&self.addr, POLL);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// Answers the requests of one connection until it closes or the server stops.
fn serve(mut stream: TcpStream, units: &Units, stop: &AtomicBool) {
    let _ = stream.set_read_timeout(Some(POLL));
    let _ = stream.set_nodelay(true);
    let mut request = [0u8; HEADER_LEN + MAX_PDU];
    let mut response = [0u8; HEADER_LEN + MAX_PDU];
    while !stop.load(Ordering::Relaxed) {
        match read_exact_or_idle(&mut stream, &mut request[..HEADER_LEN], stop) {
            Ok(true) => {}
            Ok(false) | Err(_) => return,
        }
        let Ok(header) = Header::parse(&request) else {
            return; // Out of step: the only way back is a new connection.
        };
        let body = &mut request[HEADER_LEN..HEADER_LEN + header.pdu_len];
        if !matches!(read_exact_or_idle(&mut stream, body, stop), Ok(true)) {
            return;
        }
        let to = match header.unit.0 {
            TCP_ANY_UNIT => units.first().map_or(TCP_ANY_UNIT, |u| u.0),
            BROADCAST => continue, // Not a unit over TCP: no answer, nothing done.
            id => id,
        };
        // Another unit's request: no answer, as behind a gateway.
        let Some(len) = units.handle(to, body, &mut response[HEADER_LEN..]) else {
            continue;
        };
        let reply = Header {
            pdu_len: len,
            ..header
        };
        if reply.write(&mut response).is_err()
            || stream.write_all(&response[..HEADER_LEN + len]).is_err()
        {
            return;
        }
    }
}

/// Fills `buf`; `Ok(false)` when the peer closed or the server stops.
fn read_exact_or_idle(
    stream: &mut TcpStream,
    buf: &mut [u8],
    stop: &AtomicBool,
) -> std::io::Result<bool> {
    let mut filled = 0;
    while filled < buf.len() {
        match stream.read(&mut buf[filled..]) {
            Ok(0) => return Ok(false),
            Ok(n) => filled += n,
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {
                if stop.load(Ordering::Relaxed) {
                    return Ok(false);
                }
            }
            Err(e) if e.kind() == ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(true)
}

//! Modbus TCP: a listener on a loopback (or any) address, one thread per connection, at most
//! [`MAX_CONNECTIONS`] at once, serving one drive or, as a gateway, several drives by unit id
//! ([`Units`]).

use std::io::{ErrorKind, Read, Write};
use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream, ToSocketAddrs};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

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

/// Most connections served at once. A connection beyond it makes room by closing the one that
/// has never completed a request and was opened first, else the one idle the longest: a peer
/// opening connections it never uses (half-open, or garbage it is disconnected for) cannot crowd
/// out the clients that talk.
pub const MAX_CONNECTIONS: usize = 16;

/// One open connection, as the admission policy sees it.
#[derive(Debug)]
struct Open {
    id: u64,
    stream: TcpStream,
    opened: Instant,
    /// When it last completed a request.
    served: Option<Instant>,
}

impl Open {
    /// Orders connections by how readily they are closed: never served first, oldest first.
    fn eviction_rank(&self) -> (bool, Instant) {
        (self.served.is_some(), self.served.unwrap_or(self.opened))
    }
}

/// The open connections of a server.
#[derive(Debug, Default)]
struct Connections(Mutex<Vec<Open>>);

impl Connections {
    fn open(&self) -> std::sync::MutexGuard<'_, Vec<Open>> {
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Registers connection `id`, first closing one if the server is full.
    fn admit(&self, id: u64, stream: &TcpStream) -> std::io::Result<()> {
        let stream = stream.try_clone()?;
        let mut open = self.open();
        if open.len() >= MAX_CONNECTIONS {
            if let Some(victim) = (0..open.len()).min_by_key(|&i| open[i].eviction_rank()) {
                let _ = open.swap_remove(victim).stream.shutdown(Shutdown::Both);
            }
        }
        open.push(Open {
            id,
            stream,
            opened: Instant::now(),
            served: None,
        });
        Ok(())
    }

    /// Notes that connection `id` completed a request.
    fn served(&self, id: u64) {
        if let Some(connection) = self.open().iter_mut().find(|c| c.id == id) {
            connection.served = Some(Instant::now());
        }
    }

    fn close(&self, id: u64) {
        self.open().retain(|c| c.id != id);
    }

    fn count(&self) -> usize {
        self.open().len()
    }
}

/// A running Modbus TCP server; stops when dropped.
#[derive(Debug)]
pub struct TcpServer {
    addr: SocketAddr,
    stop: Arc<AtomicBool>,
    connections: Arc<Connections>,
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
        let connections = Arc::new(Connections::default());
        let (flag, open) = (Arc::clone(&stop), Arc::clone(&connections));
        let thread = std::thread::spawn(move || {
            for (id, stream) in (0..).zip(listener.incoming()) {
                if flag.load(Ordering::Relaxed) {
                    break;
                }
                let Ok(stream) = stream else { continue };
                if open.admit(id, &stream).is_err() {
                    continue;
                }
                let units = units.clone();
                let (flag, open) = (Arc::clone(&flag), Arc::clone(&open));
                std::thread::spawn(move || {
                    let connection = Connection {
                        id,
                        open: &open,
                        stop: &flag,
                    };
                    serve(stream, &units, &connection);
                    open.close(id);
                });
            }
        });
        Ok(Self {
            addr,
            stop,
            connections,
            thread: Some(thread),
        })
    }

    /// How many connections are open (at most [`MAX_CONNECTIONS`]).
    pub fn connections(&self) -> usize {
        self.connections.count()
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

/// What a connection's thread knows of its server.
struct Connection<'a> {
    id: u64,
    open: &'a Connections,
    stop: &'a AtomicBool,
}

/// Answers the requests of one connection until it closes or the server stops.
fn serve(mut stream: TcpStream, units: &Units, connection: &Connection<'_>) {
    let stop = connection.stop;
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
        connection.open.served(connection.id);
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

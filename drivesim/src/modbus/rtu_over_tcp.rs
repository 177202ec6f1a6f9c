//! Modbus RTU over TCP: RTU frames (with their CRC) on a TCP connection, as serial device
//! servers and gateways carry them; the RTU loop of [`super::rtu`] on each accepted connection.

use std::io::{ErrorKind, Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream, ToSocketAddrs};
use std::time::{Duration, Instant};

use drivebus::modbus::client::ByteStream;
use drivebus::modbus::UnitId;
use drivebus::BusError;

use super::Units;
use crate::Simulator;

/// Shortest read timeout handed to the socket (zero would mean "block forever").
const MIN_POLL: Duration = Duration::from_millis(1);

/// Serves `unit` as Modbus RTU over TCP on `addr` (use `127.0.0.1:0` for a free port): each
/// accepted connection is served in a thread of its own until the client hangs up. Returns the
/// bound address; the listener lives as long as the process.
pub fn serve(
    sim: &Simulator,
    addr: impl ToSocketAddrs,
    unit: UnitId,
) -> std::io::Result<SocketAddr> {
    serve_units(Units::one(sim.clone(), unit), addr)
}

/// Serves every drive of `units` as Modbus RTU over TCP on `addr`, as a serial gateway in front
/// of one RS-485 line: each answers for its own unit id, other ids get no answer (see
/// [`super::rtu::serve_units`]). Returns the bound address; the listener lives as long as the
/// process.
pub fn serve_units(units: Units, addr: impl ToSocketAddrs) -> std::io::Result<SocketAddr> {
    let listener = TcpListener::bind(addr)?;
    let bound = listener.local_addr()?;
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let units = units.clone();
            // Ends with an I/O error once the client hung up.
            std::thread::spawn(move || super::rtu::serve_units(&units, &mut Connection(stream)));
        }
    });
    Ok(bound)
}

/// The server's end of one TCP connection, as the byte stream the RTU loop reads.
struct Connection(TcpStream);

fn io_error(error: std::io::Error) -> BusError {
    BusError::Io(error.kind())
}

impl ByteStream for Connection {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        self.0.write_all(bytes).map_err(io_error)
    }

    fn receive(&mut self, buf: &mut [u8], deadline: Instant) -> Result<usize, BusError> {
        let Some(left) = deadline.checked_duration_since(Instant::now()) else {
            return Ok(0);
        };
        self.0
            .set_read_timeout(Some(left.max(MIN_POLL)))
            .map_err(io_error)?;
        match self.0.read(buf) {
            // A read of nothing is the client's end of the connection, not silence.
            Ok(0) => Err(BusError::Io(ErrorKind::UnexpectedEof)),
            Ok(n) => Ok(n),
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => Ok(0),
            Err(e) => Err(io_error(e)),
        }
    }

    fn discard_input(&mut self) -> Result<(), BusError> {
        Ok(())
    }
}

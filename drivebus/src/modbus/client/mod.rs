//! Blocking Modbus clients: one request/response engine over any [`ByteStream`], with RTU or MBAP
//! framing.
//!
//! | client | stream | framing | opened with |
//! | --- | --- | --- | --- |
//! | [`SerialRtuClient`] | serial port | RTU | [`SerialRtuClient::open`] + [`SerialConfig`] |
//! | [`ModbusTcpClient`] | TCP | MBAP | [`ModbusTcpClient::connect`] + [`TcpConfig`] |
//! | [`RtuOverTcpClient`] | TCP (serial gateway) | RTU | [`RtuOverTcpClient::connect`] + [`TcpConfig`] |
//!
//! Every request: wait until the line has been idle long enough (t3.5 and the turnaround delay on
//! RTU), drop stale input, send, then read until the [`Framing`] finds the answer — skipping
//! garbage, corrupted frames and late answers to earlier requests — or the timeout passes. Failed
//! requests are repeated only as the [`RetryPolicy`] allows. Buffers live in the client: the
//! request path does not allocate.
//!
//! ```no_run
//! use std::time::Duration;
//! use drivebus::modbus::retry::{Idempotency, RetryPolicy};
//! use drivebus::modbus::rtu::Parity;
//! use drivebus::modbus::client::{
//!     ModbusTcpClient, RtuOverTcpClient, SerialConfig, SerialRtuClient, TcpConfig,
//! };
//! use drivebus::modbus::{ModbusLimits, ModbusLink, RegisterBus, Table, UnitId};
//!
//! # fn main() -> Result<(), drivebus::BusError> {
//! // RTU on a serial line: 19200 Bd, odd parity; never repeat writes to "store" or "reset".
//! let config = SerialConfig {
//!     parity: Parity::Odd,
//!     turnaround: Duration::from_millis(5),
//!     retry: RetryPolicy {
//!         retries: 2,
//!         writes_idempotent: true,
//!         non_idempotent: &[0x0000..=0x0000, 0xA5A5..=0xA5A5],
//!     },
//!     ..SerialConfig::new(19_200)
//! };
//! let mut rtu = SerialRtuClient::open("/dev/ttyUSB0", &config)?;
//! let mut status = [0u16; 17];
//! rtu.read_registers(UnitId(1), Table::Input, 0x0060, &mut status)?;
//! rtu.write_register_as(UnitId(1), 0x0000, 1, Idempotency::NonIdempotent)?;
//!
//! // Modbus TCP, and RTU frames through a serial-to-Ethernet gateway.
//! let tcp = ModbusTcpClient::connect("192.168.0.10:502", &TcpConfig::default())?;
//! let _gateway = RtuOverTcpClient::connect("192.168.0.20:4001", &TcpConfig::default())?;
//!
//! // What generated drive crates use: a Link whose batch reads go through the planner.
//! let _link = ModbusLink::new(tcp, UnitId(1), ModbusLimits::SPEC);
//! # Ok(())
//! # }
//! ```

mod pipeline;
mod rtu_over_tcp;
mod serial;
mod tcp;

use core::ops::Range;
use std::time::{Duration, Instant};

pub use super::MAX_IN_FLIGHT;
pub(crate) use crate::stream::io_error;
pub use crate::stream::{ByteStream, SerialStream};
pub use rtu_over_tcp::RtuOverTcpClient;
pub use serial::{SerialConfig, SerialRtuClient};
pub use tcp::{ModbusTcpClient, NetStream, TcpConfig};

use crate::error::BusError;

use super::framing::{scan_registers, Framing, Scan};
use super::pdu::{decode_response, Request, Response};
use super::retry::{is_transient, Idempotency, RetryPolicy};
use super::rtu::RtuFraming;
use super::tcp::TcpFraming;
use super::{read_one_by_one, BitBus, RegisterBus, RegisterRead, Table, UnitId};

/// How a client times, retries and paces requests.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ClientConfig {
    /// How long to wait for the answer to one attempt.
    pub timeout: Duration,
    /// Which failed requests are repeated.
    pub retry: RetryPolicy,
    /// Least idle time between the end of one exchange and the next request (t3.5 and the
    /// device's turnaround delay on RTU; usually zero on TCP).
    pub idle_gap: Duration,
    /// How many reads of a batch may await their answers at once (at most [`MAX_IN_FLIGHT`]).
    /// Above 1, a framing whose answers name their request (Modbus TCP) sends them together:
    /// one write and one round trip for the lot. Many servers and gateways handle one request
    /// at a time, so the default is 1.
    pub max_in_flight: usize,
}

impl Default for ClientConfig {
    fn default() -> Self {
        Self {
            timeout: Duration::from_secs(1),
            retry: RetryPolicy::reads(2),
            idle_gap: Duration::ZERO,
            max_in_flight: 1,
        }
    }
}

/// The broadcast unit id: RTU devices execute writes to it and never answer.
pub const BROADCAST: UnitId = UnitId(0);

/// Room for a little more than two ADUs, so a frame can complete behind garbage.
const RX_CAPACITY: usize = 2 * super::tcp::MAX_ADU;

/// A blocking Modbus client over stream `S` with framing `F`.
#[derive(Debug)]
pub struct Client<S, F> {
    stream: S,
    framing: F,
    config: ClientConfig,
    tx: [u8; super::tcp::MAX_ADU],
    rx: [u8; RX_CAPACITY],
    rx_len: usize,
    last_io: Option<Instant>,
    broken: bool,
    /// The unit whose answer timed out on a framing whose answers do not name their request
    /// (RTU): it may still arrive, and would pass for the answer to that unit's next request of
    /// the same shape. (Another unit's next answer is told apart by its unit id.)
    late_answer_from: Option<UnitId>,
}

/// A Modbus RTU client over any byte stream.
pub type RtuClient<S> = Client<S, RtuFraming>;
/// A Modbus TCP (MBAP) client over any byte stream.
pub type TcpClient<S> = Client<S, TcpFraming>;

impl<S: ByteStream, F: Framing> Client<S, F> {
    /// A client sending over `stream` with `framing`.
    pub fn new(stream: S, framing: F, config: ClientConfig) -> Self {
        Self {
            stream,
            framing,
            config,
            tx: [0; super::tcp::MAX_ADU],
            rx: [0; RX_CAPACITY],
            rx_len: 0,
            last_io: None,
            broken: false,
            late_answer_from: None,
        }
    }

    /// The timing and retry settings.
    pub fn config(&self) -> &ClientConfig {
        &self.config
    }

    /// Changes the timing and retry settings.
    pub fn config_mut(&mut self) -> &mut ClientConfig {
        &mut self.config
    }

    /// The underlying stream.
    pub fn stream_mut(&mut self) -> &mut S {
        &mut self.stream
    }

    /// Gives the stream back.
    pub fn into_stream(self) -> S {
        self.stream
    }

    /// Sends `request` to `unit` and returns the validated answer. `declared` overrides whether a
    /// write may be repeated (see [`RetryPolicy::is_idempotent`]). A write to [`BROADCAST`] is
    /// sent once and answers [`Response::Written`] without waiting.
    pub fn execute(
        &mut self,
        unit: UnitId,
        request: &Request<'_>,
        declared: Option<Idempotency>,
    ) -> Result<Response<'_>, BusError> {
        let attempts = self.checked_attempts(unit, request, declared)?;
        let frame = self.with_retries(attempts, |client| {
            client.exchange(unit, request, |framing, buf| {
                Ok(framing.scan(unit, request, buf))
            })
        })?;
        match frame {
            Some(range) => decode_response(request, self.framing.pdu(&self.rx[range])),
            None => Ok(Response::Written),
        }
    }

    /// Writes one holding register, stating whether the write may be repeated after a lost answer.
    pub fn write_register_as(
        &mut self,
        unit: UnitId,
        address: u16,
        value: u16,
        idempotency: Idempotency,
    ) -> Result<(), BusError> {
        let request = Request::WriteSingleRegister { address, value };
        self.execute(unit, &request, Some(idempotency)).map(drop)
    }

    /// Writes consecutive holding registers, stating whether the write may be repeated.
    pub fn write_registers_as(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
        idempotency: Idempotency,
    ) -> Result<(), BusError> {
        let request = Request::write_registers(start, values);
        self.execute(unit, &request, Some(idempotency)).map(drop)
    }

    /// Checks `request` before anything is sent; returns how many attempts it may take.
    fn checked_attempts(
        &self,
        unit: UnitId,
        request: &Request<'_>,
        declared: Option<Idempotency>,
    ) -> Result<u32, BusError> {
        request.validate()?;
        if unit == BROADCAST && !request.is_write() {
            return Err(BusError::Unsupported("reads cannot be broadcast"));
        }
        Ok(self.config.retry.attempts(request, declared))
    }

    /// Runs `attempt` up to `attempts` times while it fails transiently. Each attempt first
    /// re-establishes a broken channel, and an I/O failure marks the channel broken.
    fn with_retries<T>(
        &mut self,
        attempts: u32,
        mut attempt: impl FnMut(&mut Self) -> Result<T, BusError>,
    ) -> Result<T, BusError> {
        let mut tried = 1;
        loop {
            let result = match self.reconnect_if_broken() {
                Ok(()) => attempt(self),
                Err(error) => Err(error),
            };
            if let Err(BusError::Io(_)) = result {
                self.broken = true;
            }
            match result {
                Err(error) if tried < attempts && is_transient(&error) => tried += 1,
                result => return result,
            }
        }
    }

    fn reconnect_if_broken(&mut self) -> Result<(), BusError> {
        if self.broken {
            self.stream.reconnect()?;
            self.broken = false;
        }
        Ok(())
    }

    /// Waits out the idle gap, then drops stale input: the start of every exchange.
    fn prepare_exchange(&mut self, unit: UnitId) -> Result<(), BusError> {
        if let Some(ready) = self.last_io.map(|at| at + self.config.idle_gap) {
            let now = Instant::now();
            if ready > now {
                std::thread::sleep(ready - now);
            }
        }
        if self.late_answer_from.take() == Some(unit) {
            self.let_late_answer_pass()?;
        }
        // Before every request, even where answers carry a transaction id: the flush is also
        // where a connection the peer closed while idle is found and reopened, before anything
        // (possibly a write that must not be repeated) is sent.
        self.stream.discard_input()?;
        self.rx_len = 0;
        Ok(())
    }

    /// Before the next request to a unit whose answer timed out on RTU, listens for one more
    /// timeout and drops what arrives: the slow device's late answer would otherwise be taken for
    /// the answer to that request (RTU answers carry no transaction id). Costs one timeout after
    /// a timeout, and only when the same unit is asked again.
    fn let_late_answer_pass(&mut self) -> Result<(), BusError> {
        let until = Instant::now() + self.config.timeout;
        while Instant::now() < until && self.stream.receive(&mut self.rx, until)? != 0 {}
        Ok(())
    }

    /// Sends the `len` bytes encoded in the transmit buffer; returns the answer deadline.
    fn send_encoded(&mut self, len: usize) -> Result<Instant, BusError> {
        self.stream.send(&self.tx[..len])?;
        let sent = Instant::now();
        // Clock reads cost tens of ns; with no idle gap to keep, one per request is enough.
        if !self.config.idle_gap.is_zero() {
            self.last_io = Some(sent);
        }
        Ok(sent + self.config.timeout)
    }

    /// Receives more bytes into the receive buffer (0: the deadline passed), first making room
    /// by dropping old bytes should a misbehaving framing leave the buffer full.
    fn receive_more(&mut self, deadline: Instant) -> Result<usize, BusError> {
        if self.rx_len == self.rx.len() {
            // Unreachable with well-behaved framings (a pending frame is shorter than an ADU).
            self.drop_front(self.rx.len() / 2);
        }
        let got = self.stream.receive(&mut self.rx[self.rx_len..], deadline)?;
        self.rx_len += got;
        if got != 0 && !self.config.idle_gap.is_zero() {
            self.last_io = Some(Instant::now());
        }
        Ok(got)
    }

    /// One request and its answer; `scan` looks for the answer in the bytes received so far (and
    /// may decode it on the way, see [`scan_registers`]).
    fn exchange(
        &mut self,
        unit: UnitId,
        request: &Request<'_>,
        mut scan: impl FnMut(&F, &[u8]) -> Result<Scan, BusError>,
    ) -> Result<Option<Range<usize>>, BusError> {
        self.prepare_exchange(unit)?;
        let len = self.framing.encode_request(unit, request, &mut self.tx)?;
        let deadline = self.send_encoded(len)?;
        if unit == BROADCAST {
            return Ok(None);
        }
        let mut rejected = None;
        loop {
            match scan(&self.framing, &self.rx[..self.rx_len])? {
                Scan::Found { start, len } => return Ok(Some(start..start + len)),
                Scan::Incomplete {
                    discard,
                    rejected: why,
                } => {
                    rejected = why.or(rejected);
                    self.drop_front(discard);
                }
            }
            if self.receive_more(deadline)? == 0 {
                if !F::TAGGED_ANSWERS {
                    self.late_answer_from = Some(unit);
                }
                return Err(rejected.map_or(BusError::Timeout, BusError::Frame));
            }
        }
    }

    fn drop_front(&mut self, n: usize) {
        super::in_flight::drop_front(&mut self.rx, &mut self.rx_len, n);
    }

    fn read_into_registers(
        &mut self,
        unit: UnitId,
        request: Request<'_>,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        let attempts = self.checked_attempts(unit, &request, None)?;
        // The answer is decoded into `out` as it is found: one pass over the frame.
        self.with_retries(attempts, |client| {
            client.exchange(unit, &request, |framing, buf| {
                scan_registers(framing, unit, &request, buf, out)
            })
        })
        .map(drop)
    }

    fn read_into_bits(
        &mut self,
        unit: UnitId,
        request: Request<'_>,
        out: &mut [bool],
    ) -> Result<(), BusError> {
        match self.execute(unit, &request, None)? {
            Response::Bits(bits) => bits.copy_to(out),
            _ => Err(BusError::Frame("response does not match the request")),
        }
    }
}

fn count(items: usize) -> Result<u16, BusError> {
    u16::try_from(items).map_err(|_| BusError::Unsupported("item count outside the Modbus limits"))
}

impl<S: ByteStream, F: Framing> RegisterBus for Client<S, F> {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        let request = Request::read_registers(table, start, count(out.len())?);
        self.read_into_registers(unit, request, out)
    }

    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
        let request = Request::WriteSingleRegister { address, value };
        self.execute(unit, &request, None).map(drop)
    }

    fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        let request = Request::write_registers(start, values);
        self.execute(unit, &request, None).map(drop)
    }

    fn read_register_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        if F::TAGGED_ANSWERS && self.config.max_in_flight > 1 {
            return self.read_pipelined(unit, reads);
        }
        read_one_by_one(self, unit, reads)
    }
}

impl<S: ByteStream, F: Framing> BitBus for Client<S, F> {
    fn read_coils(&mut self, unit: UnitId, start: u16, out: &mut [bool]) -> Result<(), BusError> {
        let request = Request::ReadCoils {
            start,
            count: count(out.len())?,
        };
        self.read_into_bits(unit, request, out)
    }

    fn read_discrete_inputs(
        &mut self,
        unit: UnitId,
        start: u16,
        out: &mut [bool],
    ) -> Result<(), BusError> {
        let request = Request::ReadDiscreteInputs {
            start,
            count: count(out.len())?,
        };
        self.read_into_bits(unit, request, out)
    }

    fn write_coil(&mut self, unit: UnitId, address: u16, value: bool) -> Result<(), BusError> {
        let request = Request::WriteSingleCoil { address, value };
        self.execute(unit, &request, None).map(drop)
    }

    fn write_coils(&mut self, unit: UnitId, start: u16, values: &[bool]) -> Result<(), BusError> {
        let request = Request::write_coils(start, values);
        self.execute(unit, &request, None).map(drop)
    }
}

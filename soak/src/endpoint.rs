//! What the soak drives: eight registers behind a client, each transaction one read or one
//! non-idempotent write; and a count of the write requests the client actually sent.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::{CanBus, CanFrame, NodeId, SdoBus};
use drivebus::modbus::client::{ByteStream, Client};
use drivebus::modbus::framing::Framing;
use drivebus::modbus::retry::Idempotency;
use drivebus::modbus::{RegisterBus, Table, UnitId};
use drivebus::BusError;

/// How many registers the soak device has (`register_0` ..= `register_7`).
pub const REGISTERS: usize = 8;
/// Modbus address of `register_0`.
pub const FIRST_ADDRESS: u16 = 0x0100;
/// CANopen index of `register_0`.
pub const FIRST_INDEX: u16 = 0x2100;
/// The Modbus unit the simulator answers.
pub const UNIT: UnitId = UnitId(1);

/// A client of the soak device.
pub trait Endpoint {
    /// Reads `out.len()` registers from `first`.
    fn read(&mut self, first: usize, out: &mut [u16]) -> Result<(), BusError>;
    /// Writes `values` from `first`, declared non-idempotent (never repeated by the client).
    fn write(&mut self, first: usize, values: &[u16]) -> Result<(), BusError>;
    /// Most registers one transaction reads or writes.
    fn max_span(&self) -> usize;
    /// Write requests the client has put on the wire so far.
    fn write_requests_sent(&self) -> u64;
}

/// Counts the write requests going out on a byte stream; `function_at` is where the function
/// code sits in a request (7 in MBAP, 1 in RTU).
#[derive(Debug)]
pub struct CountingStream<S> {
    inner: S,
    function_at: usize,
    writes: Arc<AtomicU64>,
}

impl<S> CountingStream<S> {
    /// Wraps `inner`.
    pub fn new(inner: S, function_at: usize, writes: Arc<AtomicU64>) -> Self {
        Self {
            inner,
            function_at,
            writes,
        }
    }
}

impl<S: ByteStream> ByteStream for CountingStream<S> {
    fn send(&mut self, bytes: &[u8]) -> Result<(), BusError> {
        if matches!(bytes.get(self.function_at), Some(0x06 | 0x10)) {
            self.writes.fetch_add(1, Ordering::Relaxed);
        }
        self.inner.send(bytes)
    }
    fn receive(&mut self, buf: &mut [u8], deadline: Instant) -> Result<usize, BusError> {
        self.inner.receive(buf, deadline)
    }
    fn discard_input(&mut self) -> Result<(), BusError> {
        self.inner.discard_input()
    }
    fn reconnect(&mut self) -> Result<(), BusError> {
        self.inner.reconnect()
    }
}

/// The soak device over a Modbus client (TCP or RTU).
pub struct ModbusEndpoint<S, F> {
    /// The client, its stream wrapped to count writes.
    pub client: Client<CountingStream<S>, F>,
    /// The counter its stream adds to.
    pub writes: Arc<AtomicU64>,
}

impl<S: ByteStream, F: Framing> Endpoint for ModbusEndpoint<S, F> {
    fn read(&mut self, first: usize, out: &mut [u16]) -> Result<(), BusError> {
        let start = FIRST_ADDRESS + first as u16;
        self.client.read_registers(UNIT, Table::Holding, start, out)
    }

    fn write(&mut self, first: usize, values: &[u16]) -> Result<(), BusError> {
        let start = FIRST_ADDRESS + first as u16;
        match values {
            [value] => {
                self.client
                    .write_register_as(UNIT, start, *value, Idempotency::NonIdempotent)
            }
            _ => self
                .client
                .write_registers_as(UNIT, start, values, Idempotency::NonIdempotent),
        }
    }

    fn max_span(&self) -> usize {
        REGISTERS
    }

    fn write_requests_sent(&self) -> u64 {
        self.writes.load(Ordering::Relaxed)
    }
}

/// Counts the SDO download requests (client command specifier 1) going out on a CAN bus.
#[derive(Debug)]
pub struct CountingBus<B> {
    inner: B,
    writes: Arc<AtomicU64>,
}

impl<B> CountingBus<B> {
    /// Wraps `inner`.
    pub fn new(inner: B, writes: Arc<AtomicU64>) -> Self {
        Self { inner, writes }
    }
}

impl<B: CanBus> CanBus for CountingBus<B> {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        let is_sdo_request = (0x601..=0x67F).contains(&frame.id());
        if is_sdo_request && frame.data().first().is_some_and(|cs| cs >> 5 == 1) {
            self.writes.fetch_add(1, Ordering::Relaxed);
        }
        self.inner.send(frame)
    }
    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        self.inner.recv(timeout)
    }
}

/// The soak device's objects over an SDO client.
pub struct SdoEndpoint<B: CanBus> {
    /// The client.
    pub sdo: BlockingSdo<CountingBus<B>>,
    /// The simulated node.
    pub node: NodeId,
    /// The counter its bus adds to.
    pub writes: Arc<AtomicU64>,
}

impl<B: CanBus> Endpoint for SdoEndpoint<B> {
    fn read(&mut self, first: usize, out: &mut [u16]) -> Result<(), BusError> {
        for (offset, value) in out.iter_mut().enumerate() {
            let mut bytes = [0u8; 2];
            let index = FIRST_INDEX + (first + offset) as u16;
            match self.sdo.upload(self.node, index, 0, &mut bytes)? {
                2 => *value = u16::from_le_bytes(bytes),
                _ => return Err(BusError::Frame("SDO upload of the wrong size")),
            }
        }
        Ok(())
    }

    fn write(&mut self, first: usize, values: &[u16]) -> Result<(), BusError> {
        for (offset, value) in values.iter().enumerate() {
            let index = FIRST_INDEX + (first + offset) as u16;
            self.sdo
                .download(self.node, index, 0, &value.to_le_bytes())?;
        }
        Ok(())
    }

    fn max_span(&self) -> usize {
        1
    }

    fn write_requests_sent(&self) -> u64 {
        self.writes.load(Ordering::Relaxed)
    }
}

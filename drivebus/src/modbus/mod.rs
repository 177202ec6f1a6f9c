//! Modbus: addressing, a sans-I/O client core, blocking clients and (feature `server`) the
//! server's PDU codec.
//!
//! Layers, from the wire up:
//!
//! * [`pdu`] — request encoding and response decoding for FC 0x01–0x06, 0x0F and 0x10; a response
//!   is checked against the request it answers. [`exception`] types exception responses.
//! * `rtu` (feature `modbus-core`) — RTU framing: CRC-16/MODBUS (`crc`), frame scanning that
//!   resynchronises after garbage, and t1.5/t3.5 timing from the baud rate. [`tcp`] — MBAP framing.
//! * [`planner`] — the fewest read requests covering a set of values within [`ModbusLimits`].
//! * [`retry`] — which requests may be repeated after a failure, and how often.
//! * `client` (feature `modbus`) — blocking clients over a serial port, Modbus TCP and
//!   RTU-over-TCP, all implementing [`RegisterBus`] and [`BitBus`].
//!
//! [`ModbusLine`] (feature `std`) shares one line, or one gateway connection, between handles
//! for several units in several threads or async tasks, fairly.
//!
//! [`ModbusLink`] binds a [`RegisterBus`] and a unit id into a [`Link`](crate::Link): it reads and
//! writes the registers a parameter occupies and converts between registers and the little-endian
//! bytes of the value codec, honouring the parameter's word order. Batch reads go through the
//! planner.

pub(crate) use drivebus_model::modbus::address;
#[cfg(feature = "async")]
mod async_bus;
#[cfg(feature = "async")]
pub mod async_client;
#[cfg(feature = "modbus")]
pub mod client;
#[cfg(feature = "modbus-core")]
pub mod crc;
#[cfg(test)]
mod damage;
pub use drivebus_model::modbus::exception;
pub mod framing;
#[cfg(any(feature = "modbus", feature = "async"))]
mod in_flight;
#[cfg(feature = "std")]
mod line;
mod link;
pub mod pdu;
#[cfg(all(feature = "async", feature = "std"))]
pub mod pipeline;
pub mod planner;
pub mod retry;
#[cfg(feature = "modbus-core")]
pub mod rtu;
pub mod tcp;

pub use address::{
    le_to_registers, registers_to_le, ModbusAddress, ModbusLimits, RegisterSpan, Table, UnitId,
    WordOrder, MAX_VALUE_WORDS,
};
#[cfg(feature = "async")]
pub use async_bus::AsyncRegisterBus;
pub use drivebus_model::modbus::Modbus;
pub use exception::ExceptionCode;
#[cfg(feature = "std")]
#[allow(deprecated)]
pub use line::SharedBus;
#[cfg(feature = "std")]
pub use line::{LineGuard, ModbusLine};
pub use link::{LimitsSource, ModbusLink, StaticLimits};

use crate::error::BusError;

/// Most reads in flight at once: as many MBAP read requests (12 bytes) as a pipelining client's
/// transmit buffer holds, rounded down to a power of two. [`ModbusLink`]'s `read_many` hands the
/// bus this many reads at a time.
pub const MAX_IN_FLIGHT: usize = 16;

impl BusError {
    /// The exception code, if this error is a Modbus exception response.
    pub fn modbus_exception(&self) -> Option<ExceptionCode> {
        match self {
            Self::ModbusException { code, .. } => Some(*code),
            _ => None,
        }
    }
}
/// A Modbus client able to read and write registers of one unit at a time.
pub trait RegisterBus {
    /// Reads `out.len()` registers starting at `start` (FC 0x04 for input, 0x03 for holding).
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError>;
    /// Writes one holding register (FC 0x06).
    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError>;
    /// Writes consecutive holding registers (FC 0x10).
    fn write_registers(&mut self, unit: UnitId, start: u16, values: &[u16])
        -> Result<(), BusError>;
    /// Reads several register ranges of `unit`, marking each [`RegisterRead::done`] once its
    /// `out` holds the registers; on an error the reads not marked were not completed. Clients
    /// that can keep several requests in flight (Modbus TCP with
    /// `ClientConfig::max_in_flight` above 1) send them together; by default they are read one
    /// after the other.
    fn read_register_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        read_one_by_one(self, unit, reads)
    }
}

/// The batch reads of a bus that keeps one request in flight: each read not done yet, in order.
pub(crate) fn read_one_by_one<B: RegisterBus + ?Sized>(
    bus: &mut B,
    unit: UnitId,
    reads: &mut [RegisterRead<'_>],
) -> Result<(), BusError> {
    for read in reads.iter_mut().filter(|read| !read.done) {
        bus.read_registers(unit, read.table, read.start, read.out)?;
        read.done = true;
    }
    Ok(())
}

/// One range of registers in a [`RegisterBus::read_register_batch`].
#[derive(Debug)]
pub struct RegisterRead<'a> {
    /// The table read (FC 0x04 for input, 0x03 for holding registers).
    pub table: Table,
    /// Address of the first register.
    pub start: u16,
    /// Where the registers go; its length is the register count.
    pub out: &'a mut [u16],
    /// Whether `out` holds the registers: set by the bus, and reads already done are skipped.
    pub done: bool,
}

impl<'a> RegisterRead<'a> {
    /// A read of `out.len()` registers of `table` from `start`, not done yet.
    pub fn new(table: Table, start: u16, out: &'a mut [u16]) -> Self {
        Self {
            table,
            start,
            out,
            done: false,
        }
    }
}

/// A [`RegisterBus`] impl for a pointer to one (`&mut B`, `Box<B>`): every method, forwarded.
macro_rules! forward_register_bus {
    ($pointer:ty) => {
        impl<B: RegisterBus + ?Sized> RegisterBus for $pointer {
            fn read_registers(
                &mut self,
                unit: UnitId,
                table: Table,
                start: u16,
                out: &mut [u16],
            ) -> Result<(), BusError> {
                (**self).read_registers(unit, table, start, out)
            }
            fn write_register(
                &mut self,
                unit: UnitId,
                address: u16,
                value: u16,
            ) -> Result<(), BusError> {
                (**self).write_register(unit, address, value)
            }
            fn write_registers(
                &mut self,
                unit: UnitId,
                start: u16,
                values: &[u16],
            ) -> Result<(), BusError> {
                (**self).write_registers(unit, start, values)
            }
            fn read_register_batch(
                &mut self,
                unit: UnitId,
                reads: &mut [RegisterRead<'_>],
            ) -> Result<(), BusError> {
                (**self).read_register_batch(unit, reads)
            }
        }
    };
}

forward_register_bus!(&mut B);
// A boxed client: the CLI keeps whichever client the options opened behind one type.
#[cfg(feature = "std")]
forward_register_bus!(std::boxed::Box<B>);

/// A Modbus client able to read and write single-bit data (coils and discrete inputs).
pub trait BitBus {
    /// Reads `out.len()` coils starting at `start` (FC 0x01).
    fn read_coils(&mut self, unit: UnitId, start: u16, out: &mut [bool]) -> Result<(), BusError>;
    /// Reads `out.len()` discrete inputs starting at `start` (FC 0x02).
    fn read_discrete_inputs(
        &mut self,
        unit: UnitId,
        start: u16,
        out: &mut [bool],
    ) -> Result<(), BusError>;
    /// Writes one coil (FC 0x05).
    fn write_coil(&mut self, unit: UnitId, address: u16, value: bool) -> Result<(), BusError>;
    /// Writes consecutive coils (FC 0x0F).
    fn write_coils(&mut self, unit: UnitId, start: u16, values: &[bool]) -> Result<(), BusError>;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bus_errors_tell_their_exception_code() {
        let error = BusError::ModbusException {
            function: 3,
            code: ExceptionCode::from(2),
        };
        assert_eq!(
            error.modbus_exception(),
            Some(ExceptionCode::IllegalDataAddress)
        );
        assert_eq!(BusError::Timeout.modbus_exception(), None);
    }
}

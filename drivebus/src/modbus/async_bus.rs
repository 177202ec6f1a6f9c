//! [`AsyncRegisterBus`], the async twin of [`RegisterBus`](super::RegisterBus), and
//! [`ModbusLink`] as an [`AsyncLink`] over one: the link's checks, register conversions and
//! batch planning are the blocking link's, only the bus calls are awaited.

use crate::asynch::AsyncLink;
use crate::error::BusError;
use crate::link::ReadRequest;

use super::address::{ModbusAddress, Table, UnitId, MAX_VALUE_WORDS};
use super::link::{value_from, Rounds, StaticLimits, WritePlan, MAX_BATCH};
use super::pdu::MAX_READ_REGISTERS;
use super::{Modbus, ModbusLink, RegisterRead};

/// An async Modbus client able to read and write registers of one unit at a time: the async
/// twin of [`RegisterBus`](super::RegisterBus), method by method.
///
/// Dropping one of its futures mid-request leaves the bus usable: the next request is not
/// answered by the dropped one's answer (Modbus TCP: discarded by its transaction id; RTU: the
/// line is resynchronised first).
#[allow(async_fn_in_trait)] // as `AsyncLink`: no `Send` bound that single-threaded executors lack
pub trait AsyncRegisterBus {
    /// Reads `out.len()` registers starting at `start` (FC 0x04 for input, 0x03 for holding).
    async fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError>;
    /// Writes one holding register (FC 0x06).
    async fn write_register(
        &mut self,
        unit: UnitId,
        address: u16,
        value: u16,
    ) -> Result<(), BusError>;
    /// Writes consecutive holding registers (FC 0x10).
    async fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError>;
    /// Reads several register ranges of `unit`, marking each [`RegisterRead::done`] once its
    /// `out` holds the registers, as [`RegisterBus::read_register_batch`](super::RegisterBus::read_register_batch).
    /// By default they are read one after the other.
    async fn read_register_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        for read in reads.iter_mut().filter(|read| !read.done) {
            self.read_registers(unit, read.table, read.start, read.out)
                .await?;
            read.done = true;
        }
        Ok(())
    }
}

impl<B: AsyncRegisterBus + ?Sized> AsyncRegisterBus for &mut B {
    async fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        (**self).read_registers(unit, table, start, out).await
    }
    async fn write_register(
        &mut self,
        unit: UnitId,
        address: u16,
        value: u16,
    ) -> Result<(), BusError> {
        (**self).write_register(unit, address, value).await
    }
    async fn write_registers(
        &mut self,
        unit: UnitId,
        start: u16,
        values: &[u16],
    ) -> Result<(), BusError> {
        (**self).write_registers(unit, start, values).await
    }
    async fn read_register_batch(
        &mut self,
        unit: UnitId,
        reads: &mut [RegisterRead<'_>],
    ) -> Result<(), BusError> {
        (**self).read_register_batch(unit, reads).await
    }
}

// Over `StaticLimits`, not `ModbusLimits<'a>`: see `StaticLimits` for why no lifetime.
impl<B: AsyncRegisterBus> AsyncLink for ModbusLink<B, StaticLimits> {
    type Protocol = Modbus;

    async fn read(&mut self, address: &ModbusAddress, out: &mut [u8]) -> Result<usize, BusError> {
        let mut registers = [0u16; MAX_VALUE_WORDS];
        let registers = &mut registers[..self.read_words(address)?];
        let unit = self.unit();
        let bus = self.bus_mut();
        bus.read_registers(unit, address.table, address.address, registers)
            .await?;
        value_from(registers, address, out)
    }

    async fn write(&mut self, address: &ModbusAddress, data: &[u8]) -> Result<(), BusError> {
        let mut registers = [0u16; MAX_VALUE_WORDS];
        let (unit, start) = (self.unit(), address.address);
        let plan = self.write_plan(address, data, &mut registers)?;
        let bus = self.bus_mut();
        match plan {
            WritePlan::Single => bus.write_register(unit, start, registers[0]).await,
            WritePlan::Multiple(n) => bus.write_registers(unit, start, &registers[..n]).await,
            WritePlan::OneByOne(n) => {
                for (i, word) in registers[..n].iter().enumerate() {
                    bus.write_register(unit, start + i as u16, *word).await?;
                }
                Ok(())
            }
        }
    }

    fn wire_bytes(&self, address: &ModbusAddress) -> usize {
        address.words as usize * 2
    }

    fn failed_request(&self, requests: &[ReadRequest<'_, ModbusAddress>]) -> Option<usize> {
        self.failed_in(requests)
    }

    /// The batch in the fewest requests the device's limits allow, as the blocking link plans
    /// it; each round of reads is handed to the bus at once, so a pipelining client keeps
    /// them in flight together.
    async fn read_many(
        &mut self,
        requests: &mut [ReadRequest<'_, ModbusAddress>],
    ) -> Result<(), BusError> {
        let (unit, limits) = (self.unit(), *self.static_limits());
        let mut rounds = Rounds::new(requests);
        let mut registers = [[0u16; MAX_READ_REGISTERS as usize]; MAX_BATCH];
        while let Some((mut reads, count)) = rounds.next(&limits, &mut registers)? {
            let outcome = self
                .bus_mut()
                .read_register_batch(unit, &mut reads[..count])
                .await;
            rounds.delivered(&reads[..count], outcome)?;
        }
        Ok(())
    }
}

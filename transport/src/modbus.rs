//! Modbus addressing and the register-bus trait that Modbus transports implement.
//!
//! [`ModbusLink`] binds a [`RegisterBus`] and a unit id into a [`Link`]: it reads and writes the
//! registers a parameter occupies and converts between registers and the little-endian bytes of the
//! value codec, honouring the parameter's word order.

use crate::error::BusError;
use crate::link::{Link, ReadRequest};
use crate::Protocol;

/// The Modbus protocol marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Modbus;

impl Protocol for Modbus {
    type Address = ModbusAddress;
    const NAME: &'static str = "Modbus";
}

/// A Modbus data table. Input and holding registers are separate address spaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Table {
    /// Read-only 16-bit registers (FC 0x04).
    Input,
    /// Read/write 16-bit registers (FC 0x03, 0x06, 0x10).
    Holding,
}

/// Order of the 16-bit words of a multi-register value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum WordOrder {
    /// Most significant word at the lowest address (Modbus convention).
    HighFirst,
    /// Least significant word at the lowest address (Lafert LOW/HIGH pairs, Kinco).
    LowFirst,
}

/// Where a parameter lives on a Modbus device.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ModbusAddress {
    /// Register table.
    pub table: Table,
    /// PDU address of the first register (0-based, as on the wire).
    pub address: u16,
    /// Number of 16-bit registers the value occupies.
    pub words: u16,
    /// Word order when `words > 1`.
    pub word_order: WordOrder,
}

/// A Modbus unit (slave) id.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct UnitId(pub u8);

/// What a device accepts, from its description; the link and the request planner respect it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ModbusLimits {
    /// Most registers one read request may ask for (Lenze smd: 1).
    pub max_read_registers: u16,
    /// Most registers one write request may carry.
    pub max_write_registers: u16,
    /// Whether the device implements FC 0x10 (write multiple registers).
    pub write_multiple: bool,
    /// Whether a read may span addresses the description does not list.
    pub read_gaps: bool,
}

impl ModbusLimits {
    /// The limits of the Modbus specification itself.
    pub const SPEC: ModbusLimits = ModbusLimits {
        max_read_registers: 125,
        max_write_registers: 123,
        write_multiple: true,
        read_gaps: true,
    };
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
}

impl<B: RegisterBus + ?Sized> RegisterBus for &mut B {
    fn read_registers(
        &mut self,
        unit: UnitId,
        table: Table,
        start: u16,
        out: &mut [u16],
    ) -> Result<(), BusError> {
        (**self).read_registers(unit, table, start, out)
    }
    fn write_register(&mut self, unit: UnitId, address: u16, value: u16) -> Result<(), BusError> {
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
}

/// Most registers one value may occupy (a 64-byte string); larger values are refused.
pub const MAX_VALUE_WORDS: usize = 32;

/// Registers → little-endian value bytes, in the given word order. `out` holds `2 × regs` bytes.
pub fn registers_to_le(registers: &[u16], order: WordOrder, out: &mut [u8]) {
    let n = registers.len();
    for (i, chunk) in out.chunks_exact_mut(2).enumerate().take(n) {
        let word = match order {
            WordOrder::LowFirst => registers[i],
            WordOrder::HighFirst => registers[n - 1 - i],
        };
        chunk.copy_from_slice(&word.to_le_bytes());
    }
}

/// Little-endian value bytes → registers, in the given word order (inverse of [`registers_to_le`]).
pub fn le_to_registers(bytes: &[u8], order: WordOrder, out: &mut [u16]) {
    let n = out.len();
    for (i, chunk) in bytes.chunks_exact(2).enumerate().take(n) {
        let word = u16::from_le_bytes([chunk[0], chunk[1]]);
        match order {
            WordOrder::LowFirst => out[i] = word,
            WordOrder::HighFirst => out[n - 1 - i] = word,
        }
    }
}

/// A [`RegisterBus`] bound to one unit: the [`Link`] generated Modbus drive handles use.
#[derive(Debug)]
pub struct ModbusLink<B> {
    bus: B,
    unit: UnitId,
    limits: ModbusLimits,
}

impl<B: RegisterBus> ModbusLink<B> {
    /// Binds `bus` to `unit`, respecting the device's `limits`.
    pub fn new(bus: B, unit: UnitId, limits: ModbusLimits) -> Self {
        Self { bus, unit, limits }
    }
    /// The unit this link talks to.
    pub fn unit(&self) -> UnitId {
        self.unit
    }
    /// The device limits this link respects.
    pub fn limits(&self) -> ModbusLimits {
        self.limits
    }
    /// The underlying bus.
    pub fn bus_mut(&mut self) -> &mut B {
        &mut self.bus
    }
    /// Gives the bus back.
    pub fn into_bus(self) -> B {
        self.bus
    }
}

fn value_words(address: &ModbusAddress) -> Result<usize, BusError> {
    let words = address.words as usize;
    if words == 0 || words > MAX_VALUE_WORDS {
        return Err(BusError::Unsupported("value wider than 32 registers"));
    }
    Ok(words)
}

impl<B: RegisterBus> Link for ModbusLink<B> {
    type Protocol = Modbus;

    fn read(&mut self, address: &ModbusAddress, out: &mut [u8]) -> Result<usize, BusError> {
        let words = value_words(address)?;
        if words > self.limits.max_read_registers as usize {
            return Err(BusError::Unsupported(
                "value wider than the device's read limit",
            ));
        }
        let mut registers = [0u16; MAX_VALUE_WORDS];
        let registers = &mut registers[..words];
        self.bus
            .read_registers(self.unit, address.table, address.address, registers)?;
        let bytes = out
            .get_mut(..words * 2)
            .ok_or(BusError::Frame("value buffer too small"))?;
        registers_to_le(registers, address.word_order, bytes);
        Ok(words * 2)
    }

    fn write(&mut self, address: &ModbusAddress, data: &[u8]) -> Result<(), BusError> {
        if address.table != Table::Holding {
            return Err(BusError::Unsupported(
                "only holding registers can be written",
            ));
        }
        let words = value_words(address)?;
        if data.len() != words * 2 {
            return Err(BusError::Frame(
                "value length does not match its register count",
            ));
        }
        let mut registers = [0u16; MAX_VALUE_WORDS];
        let registers = &mut registers[..words];
        le_to_registers(data, address.word_order, registers);
        if words == 1 {
            self.bus
                .write_register(self.unit, address.address, registers[0])
        } else if self.limits.write_multiple && words <= self.limits.max_write_registers as usize {
            self.bus
                .write_registers(self.unit, address.address, registers)
        } else {
            // Without FC 0x10 the words go one by one, lowest address first; the device sees the
            // value torn for a moment, which the description's word order makes explicit.
            for (i, word) in registers.iter().enumerate() {
                self.bus
                    .write_register(self.unit, address.address + i as u16, *word)?;
            }
            Ok(())
        }
    }

    fn wire_bytes(&self, address: &ModbusAddress) -> usize {
        address.words as usize * 2
    }

    fn read_many(
        &mut self,
        requests: &mut [ReadRequest<'_, ModbusAddress>],
    ) -> Result<(), BusError> {
        for request in requests.iter_mut() {
            request.len = self.read(&request.address, request.buf)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn low_first_pair_becomes_little_endian_bytes() {
        let mut out = [0u8; 4];
        registers_to_le(&[0x5678, 0x1234], WordOrder::LowFirst, &mut out);
        assert_eq!(u32::from_le_bytes(out), 0x1234_5678);
        registers_to_le(&[0x1234, 0x5678], WordOrder::HighFirst, &mut out);
        assert_eq!(u32::from_le_bytes(out), 0x1234_5678);
    }

    #[test]
    fn register_conversion_round_trips() {
        for order in [WordOrder::LowFirst, WordOrder::HighFirst] {
            let bytes = 0x0102_0304_0506_0708u64.to_le_bytes();
            let mut regs = [0u16; 4];
            le_to_registers(&bytes, order, &mut regs);
            let mut back = [0u8; 8];
            registers_to_le(&regs, order, &mut back);
            assert_eq!(back, bytes);
        }
    }
}

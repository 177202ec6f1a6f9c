//! Where values live on a Modbus device, what the device accepts, and register ↔ byte conversion.

/// A Modbus data table. Input and holding registers are separate address spaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "kebab-case"))]
pub enum Table {
    /// Read-only 16-bit registers (FC 0x04).
    Input,
    /// Read/write 16-bit registers (FC 0x03, 0x06, 0x10).
    Holding,
}

impl Table {
    /// The table's name as a description writes it (`table = "holding"`).
    pub const fn name(self) -> &'static str {
        match self {
            Table::Input => "input",
            Table::Holding => "holding",
        }
    }
}

/// Order of the 16-bit words of a multi-register value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "kebab-case"))]
pub enum WordOrder {
    /// Most significant word at the lowest address (Modbus convention).
    HighFirst,
    /// Least significant word at the lowest address (Lafert LOW/HIGH pairs, Kinco).
    LowFirst,
    /// A byte string (text, octets): its bytes in address order, each register high byte
    /// first, the Modbus convention for text (Lenze smd C99 "SMD 1.51", lines 926 and 639).
    /// Strings have no numeric word order; the description's loader gives them this one.
    Text,
}

/// Where a parameter lives on a Modbus device.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
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

impl ModbusAddress {
    /// A value in the input registers.
    pub const fn input(address: u16, words: u16, word_order: WordOrder) -> Self {
        Self {
            table: Table::Input,
            address,
            words,
            word_order,
        }
    }

    /// A value in the holding registers.
    pub const fn holding(address: u16, words: u16, word_order: WordOrder) -> Self {
        Self {
            table: Table::Holding,
            address,
            words,
            word_order,
        }
    }
}

/// A Modbus unit (slave) id.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct UnitId(pub u8);

/// What a device accepts, from its description; the link and the request planner respect it.
///
/// Generated code holds `ModbusLimits<'static>` constants; a tool that loads a description at run
/// time lends a view of its own register lists.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ModbusLimits<'a> {
    /// Most registers one read request may ask for (Lenze smd: 1).
    pub max_read_registers: u16,
    /// Most registers one write request may carry.
    pub max_write_registers: u16,
    /// Whether the device implements FC 0x10 (write multiple registers).
    pub write_multiple: bool,
    /// Whether a read may span addresses the description does not list.
    pub read_gaps: bool,
    /// Where `read_gaps` is false: the registers the description lists as readable, as runs
    /// sorted by table and address, which a read may cover besides the requested ones. Empty:
    /// a read covers requested registers only.
    pub readable: &'a [RegisterSpan],
    /// The registers the description lists without read access (write-only ones), as runs: no
    /// read covers them besides the requested ones, even where `read_gaps` allows unlisted
    /// addresses — the device would refuse the whole request.
    pub unreadable: &'a [RegisterSpan],
    /// Reads the device answers beyond `max_read_registers`, exactly as listed (the description's
    /// `[modbus] read_blocks`; Lenze smd: 6 words at #24). The planner reads a whole block where
    /// that takes fewer requests than reading its values one by one.
    pub read_blocks: &'a [RegisterSpan],
    /// Values wider than `max_read_registers` the device answers whole, each in one read of
    /// exactly its words at its address (a Modbus address whose `occupies` is less than its
    /// `words`; Lenze smd C99, 4 words at one register). Such a read covers that value only.
    pub whole_values: &'a [RegisterSpan],
}

/// Consecutive registers of one table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RegisterSpan {
    /// The table.
    pub table: Table,
    /// First register.
    pub start: u16,
    /// How many registers.
    pub count: u16,
}

impl RegisterSpan {
    /// `count` input registers from `start`.
    pub const fn input(start: u16, count: u16) -> Self {
        Self {
            table: Table::Input,
            start,
            count,
        }
    }

    /// `count` holding registers from `start`.
    pub const fn holding(start: u16, count: u16) -> Self {
        Self {
            table: Table::Holding,
            start,
            count,
        }
    }

    /// One past the last register.
    pub fn end(&self) -> usize {
        self.start as usize + self.count as usize
    }

    /// Whether this span is exactly the registers of `value`.
    pub fn is_exactly(&self, value: &ModbusAddress) -> bool {
        self.table == value.table && self.start == value.address && self.count == value.words
    }
}

impl ModbusLimits<'static> {
    /// The limits of the Modbus specification itself.
    pub const SPEC: ModbusLimits<'static> = ModbusLimits {
        max_read_registers: 125,
        max_write_registers: 123,
        write_multiple: true,
        read_gaps: true,
        readable: &[],
        unreadable: &[],
        read_blocks: &[],
        whole_values: &[],
    };
}

/// Most registers one value may occupy (a 64-byte string); larger values are refused.
pub const MAX_VALUE_WORDS: usize = 32;

/// Registers → little-endian value bytes, in the given word order. `out` holds `2 × regs` bytes.
pub fn registers_to_le(registers: &[u16], order: WordOrder, out: &mut [u8]) {
    let n = registers.len();
    for (i, chunk) in out.chunks_exact_mut(2).enumerate().take(n) {
        let bytes = match order {
            WordOrder::LowFirst => registers[i].to_le_bytes(),
            WordOrder::HighFirst => registers[n - 1 - i].to_le_bytes(),
            WordOrder::Text => registers[i].to_be_bytes(),
        };
        chunk.copy_from_slice(&bytes);
    }
}

/// Little-endian value bytes → registers, in the given word order (inverse of [`registers_to_le`]).
pub fn le_to_registers(bytes: &[u8], order: WordOrder, out: &mut [u16]) {
    let n = out.len();
    for (i, chunk) in bytes.chunks_exact(2).enumerate().take(n) {
        let pair = [chunk[0], chunk[1]];
        match order {
            WordOrder::LowFirst => out[i] = u16::from_le_bytes(pair),
            WordOrder::HighFirst => out[n - 1 - i] = u16::from_le_bytes(pair),
            WordOrder::Text => out[i] = u16::from_be_bytes(pair),
        }
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
    fn text_runs_in_address_order_high_byte_first() {
        let registers = [0x534D, 0x4420, 0x312E, 0x3531];
        let mut out = [0u8; 8];
        registers_to_le(&registers, WordOrder::Text, &mut out);
        assert_eq!(&out, b"SMD 1.51");
        let mut back = [0u16; 4];
        le_to_registers(&out, WordOrder::Text, &mut back);
        assert_eq!(back, registers);
    }

    #[test]
    fn register_conversion_round_trips() {
        for order in [WordOrder::LowFirst, WordOrder::HighFirst, WordOrder::Text] {
            let bytes = 0x0102_0304_0506_0708u64.to_le_bytes();
            let mut regs = [0u16; 4];
            le_to_registers(&bytes, order, &mut regs);
            let mut back = [0u8; 8];
            registers_to_le(&regs, order, &mut back);
            assert_eq!(back, bytes);
        }
    }
}

//! The one Modbus request type: what a client encodes and sends, and what a server decodes.

use crate::error::BusError;
use crate::modbus::address::Table;

use super::*;

/// A Modbus request, as a client builds and encodes it ([`Request::encode`]) and as a server
/// decodes it (`decode_request`, feature `server`). Write payloads are [`Bits`] and
/// [`Registers`]: the client's own values, or the frame's bytes on the server side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Request<'a> {
    /// FC 0x01.
    ReadCoils {
        /// First coil.
        start: u16,
        /// Number of coils, 1..=2000.
        count: u16,
    },
    /// FC 0x02.
    ReadDiscreteInputs {
        /// First input.
        start: u16,
        /// Number of inputs, 1..=2000.
        count: u16,
    },
    /// FC 0x03.
    ReadHoldingRegisters {
        /// First register.
        start: u16,
        /// Number of registers, 1..=125.
        count: u16,
    },
    /// FC 0x04.
    ReadInputRegisters {
        /// First register.
        start: u16,
        /// Number of registers, 1..=125.
        count: u16,
    },
    /// FC 0x05.
    WriteSingleCoil {
        /// Coil address.
        address: u16,
        /// New state.
        value: bool,
    },
    /// FC 0x06.
    WriteSingleRegister {
        /// Register address.
        address: u16,
        /// New value.
        value: u16,
    },
    /// FC 0x0F.
    WriteMultipleCoils {
        /// First coil.
        start: u16,
        /// New states, 1..=1968.
        values: Bits<'a>,
    },
    /// FC 0x10.
    WriteMultipleRegisters {
        /// First register.
        start: u16,
        /// New values, 1..=123.
        values: Registers<'a>,
    },
}

impl<'a> Request<'a> {
    /// The read request for `count` registers of `table` from `start`.
    #[inline]
    pub const fn read_registers(table: Table, start: u16, count: u16) -> Self {
        match table {
            Table::Input => Self::ReadInputRegisters { start, count },
            Table::Holding => Self::ReadHoldingRegisters { start, count },
        }
    }

    /// The write of `values` to the holding registers from `start` (FC 0x10).
    #[inline]
    pub const fn write_registers(start: u16, values: &'a [u16]) -> Self {
        Self::WriteMultipleRegisters {
            start,
            values: Registers::from_values(values),
        }
    }

    /// The write of `values` to the coils from `start` (FC 0x0F).
    #[inline]
    pub const fn write_coils(start: u16, values: &'a [bool]) -> Self {
        Self::WriteMultipleCoils {
            start,
            values: Bits::from_values(values),
        }
    }

    /// The function code.
    #[inline]
    pub const fn function(&self) -> u8 {
        match self {
            Self::ReadCoils { .. } => function::READ_COILS,
            Self::ReadDiscreteInputs { .. } => function::READ_DISCRETE_INPUTS,
            Self::ReadHoldingRegisters { .. } => function::READ_HOLDING_REGISTERS,
            Self::ReadInputRegisters { .. } => function::READ_INPUT_REGISTERS,
            Self::WriteSingleCoil { .. } => function::WRITE_SINGLE_COIL,
            Self::WriteSingleRegister { .. } => function::WRITE_SINGLE_REGISTER,
            Self::WriteMultipleCoils { .. } => function::WRITE_MULTIPLE_COILS,
            Self::WriteMultipleRegisters { .. } => function::WRITE_MULTIPLE_REGISTERS,
        }
    }

    /// Whether the request changes the device (writes are not retried blindly).
    #[inline]
    pub const fn is_write(&self) -> bool {
        matches!(
            self,
            Self::WriteSingleCoil { .. }
                | Self::WriteSingleRegister { .. }
                | Self::WriteMultipleCoils { .. }
                | Self::WriteMultipleRegisters { .. }
        )
    }

    /// First address and number of items the request touches.
    #[inline]
    pub fn span(&self) -> (u16, usize) {
        match *self {
            Self::ReadCoils { start, count }
            | Self::ReadDiscreteInputs { start, count }
            | Self::ReadHoldingRegisters { start, count }
            | Self::ReadInputRegisters { start, count } => (start, count as usize),
            Self::WriteSingleCoil { address, .. } | Self::WriteSingleRegister { address, .. } => {
                (address, 1)
            }
            Self::WriteMultipleCoils { start, values } => (start, values.len()),
            Self::WriteMultipleRegisters { start, values } => (start, values.len()),
        }
    }

    /// Checks counts against the specification's limits and the address space.
    #[inline]
    pub fn validate(&self) -> Result<(), BusError> {
        let (start, count) = self.span();
        let max = match self {
            Self::ReadCoils { .. } | Self::ReadDiscreteInputs { .. } => MAX_READ_BITS,
            Self::ReadHoldingRegisters { .. } | Self::ReadInputRegisters { .. } => {
                MAX_READ_REGISTERS
            }
            Self::WriteSingleCoil { .. } | Self::WriteSingleRegister { .. } => 1,
            Self::WriteMultipleCoils { .. } => MAX_WRITE_BITS,
            Self::WriteMultipleRegisters { .. } => MAX_WRITE_REGISTERS,
        };
        check_span(start, count, max)
    }

    /// Length of the encoded request PDU.
    #[inline]
    pub fn encoded_len(&self) -> usize {
        match self {
            Self::WriteMultipleCoils { values, .. } => 6 + bit_bytes(values.len()),
            Self::WriteMultipleRegisters { values, .. } => 6 + 2 * values.len(),
            _ => 5,
        }
    }

    /// Length of the normal (non-exception) response PDU.
    #[inline]
    pub fn response_len(&self) -> usize {
        match *self {
            Self::ReadCoils { count, .. } | Self::ReadDiscreteInputs { count, .. } => {
                2 + bit_bytes(count as usize)
            }
            Self::ReadHoldingRegisters { count, .. } | Self::ReadInputRegisters { count, .. } => {
                2 + 2 * count as usize
            }
            _ => 5,
        }
    }

    /// For a register read, what its normal answer PDU must be: the function code and byte count it
    /// starts with, and its length. `None` for other requests, and for counts no byte count can
    /// express (validation refuses those before sending).
    #[inline]
    pub fn register_answer(&self) -> Option<([u8; 2], usize)> {
        match *self {
            Self::ReadHoldingRegisters { count, .. } | Self::ReadInputRegisters { count, .. } => {
                let bytes = u8::try_from(2 * count as usize).ok()?;
                Some(([self.function(), bytes], 2 + usize::from(bytes)))
            }
            _ => None,
        }
    }

    /// Encodes the PDU into `out`; returns its length.
    #[inline]
    pub fn encode(&self, out: &mut [u8]) -> Result<usize, BusError> {
        // One dispatch: each arm validates and writes its own fields (this is the hot path).
        let (function, first, second, max) = match *self {
            Self::ReadCoils { start, count } => (function::READ_COILS, start, count, MAX_READ_BITS),
            Self::ReadDiscreteInputs { start, count } => {
                (function::READ_DISCRETE_INPUTS, start, count, MAX_READ_BITS)
            }
            Self::ReadHoldingRegisters { start, count } => (
                function::READ_HOLDING_REGISTERS,
                start,
                count,
                MAX_READ_REGISTERS,
            ),
            Self::ReadInputRegisters { start, count } => (
                function::READ_INPUT_REGISTERS,
                start,
                count,
                MAX_READ_REGISTERS,
            ),
            Self::WriteSingleCoil { address, value } => (
                function::WRITE_SINGLE_COIL,
                address,
                if value { COIL_ON } else { COIL_OFF },
                u16::MAX,
            ),
            Self::WriteSingleRegister { address, value } => {
                (function::WRITE_SINGLE_REGISTER, address, value, u16::MAX)
            }
            Self::WriteMultipleCoils { .. } | Self::WriteMultipleRegisters { .. } => {
                return self.encode_multiple(out);
            }
        };
        if max != u16::MAX {
            check_span(first, second as usize, max)?;
        }
        let head = out.get_mut(..5).ok_or(BusError::Unsupported(
            "output buffer too small for the request",
        ))?;
        let [a, b] = first.to_be_bytes();
        let [c, d] = second.to_be_bytes();
        head.copy_from_slice(&[function, a, b, c, d]);
        Ok(5)
    }

    fn encode_multiple(&self, out: &mut [u8]) -> Result<usize, BusError> {
        self.validate()?;
        let len = self.encoded_len();
        let out = out.get_mut(..len).ok_or(BusError::Unsupported(
            "output buffer too small for the request",
        ))?;
        let (start, count) = self.span();
        out[0] = self.function();
        out[1..3].copy_from_slice(&start.to_be_bytes());
        out[3..5].copy_from_slice(&(count as u16).to_be_bytes());
        out[5] = (len - 6) as u8;
        match *self {
            Self::WriteMultipleCoils { values, .. } => values.write_wire(&mut out[6..]),
            Self::WriteMultipleRegisters { values, .. } => values.write_wire(&mut out[6..]),
            _ => {}
        }
        Ok(len)
    }
}

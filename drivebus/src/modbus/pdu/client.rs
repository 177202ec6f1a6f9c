//! The client side: requests encoded into PDUs, and response PDUs decoded against the request
//! they answer.

use crate::error::BusError;
use crate::modbus::address::Table;
use crate::modbus::exception::ExceptionCode;

use super::*;

/// A client request.
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
        values: &'a [bool],
    },
    /// FC 0x10.
    WriteMultipleRegisters {
        /// First register.
        start: u16,
        /// New values, 1..=123.
        values: &'a [u16],
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
            Self::WriteMultipleCoils { values, .. } => pack_bits(values, &mut out[6..]),
            Self::WriteMultipleRegisters { values, .. } => {
                for (chunk, value) in out[6..].chunks_exact_mut(2).zip(values) {
                    chunk.copy_from_slice(&value.to_be_bytes());
                }
            }
            _ => {}
        }
        Ok(len)
    }
}

/// Registers of a read response, still in wire (big-endian) form; borrowed from the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Registers<'a> {
    bytes: &'a [u8],
}

impl<'a> Registers<'a> {
    /// Views big-endian register bytes; an odd trailing byte is ignored.
    #[inline]
    pub fn new(bytes: &'a [u8]) -> Self {
        Self {
            bytes: &bytes[..bytes.len() & !1],
        }
    }
    /// Number of registers.
    #[inline]
    pub fn len(&self) -> usize {
        self.bytes.len() / 2
    }
    /// Whether there are none.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }
    /// Register `i`, if present.
    #[inline]
    pub fn get(&self, i: usize) -> Option<u16> {
        let pair = self.bytes.get(2 * i..2 * i + 2)?;
        Some(u16::from_be_bytes([pair[0], pair[1]]))
    }
    /// The registers in address order.
    #[inline]
    pub fn iter(&self) -> impl Iterator<Item = u16> + 'a {
        self.bytes
            .chunks_exact(2)
            .map(|pair| u16::from_be_bytes([pair[0], pair[1]]))
    }
    /// Copies the registers into `out`, which must have exactly [`len`](Self::len) slots.
    #[inline]
    pub fn copy_to(&self, out: &mut [u16]) -> Result<(), BusError> {
        if out.len() != self.len() {
            return Err(frame_error("register count does not match the request"));
        }
        for (slot, value) in out.iter_mut().zip(self.iter()) {
            *slot = value;
        }
        Ok(())
    }
}

/// Bits of a read response (coils or discrete inputs), packed LSB first; borrowed from the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bits<'a> {
    bytes: &'a [u8],
    count: usize,
}

impl<'a> Bits<'a> {
    /// Views `count` packed bits (fewer if `bytes` is short).
    #[inline]
    pub fn new(bytes: &'a [u8], count: usize) -> Self {
        Self {
            bytes,
            count: count.min(bytes.len() * 8),
        }
    }
    /// Number of bits.
    #[inline]
    pub fn len(&self) -> usize {
        self.count
    }
    /// Whether there are none.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }
    /// Bit `i`, if present.
    #[inline]
    pub fn get(&self, i: usize) -> Option<bool> {
        if i >= self.count {
            return None;
        }
        Some(self.bytes[i / 8] & (1 << (i % 8)) != 0)
    }
    /// Copies the bits into `out`, which must have exactly [`len`](Self::len) slots.
    #[inline]
    pub fn copy_to(&self, out: &mut [bool]) -> Result<(), BusError> {
        if out.len() != self.count {
            return Err(frame_error("bit count does not match the request"));
        }
        for (i, slot) in out.iter_mut().enumerate() {
            *slot = self.bytes[i / 8] & (1 << (i % 8)) != 0;
        }
        Ok(())
    }
}

/// A decoded normal response.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Response<'a> {
    /// FC 0x03 / 0x04.
    Registers(Registers<'a>),
    /// FC 0x01 / 0x02.
    Bits(Bits<'a>),
    /// A write was confirmed by an echo that matches the request.
    Written,
}

/// Decodes the response PDU `pdu` to `request`.
///
/// Anything that is not exactly the answer to this request — another function code, a byte
/// count or echo that does not match, a wrong length — is rejected; an exception response becomes
/// [`BusError::ModbusException`].
#[inline]
pub fn decode_response<'a>(request: &Request<'_>, pdu: &'a [u8]) -> Result<Response<'a>, BusError> {
    match register_data(request, pdu) {
        Some(bytes) => Ok(Response::Registers(Registers { bytes })),
        None => decode_any_response(request, pdu),
    }
}

/// Decodes the response PDU `pdu` to register read `request` straight into `out`, which must have
/// one slot per requested register.
///
/// Accepts and rejects exactly what [`decode_response`] followed by [`Registers::copy_to`] does,
/// with the same errors; a well-formed answer is checked and copied in one pass. `out` is only
/// written when the answer is accepted.
#[inline]
pub fn decode_registers(
    request: &Request<'_>,
    pdu: &[u8],
    out: &mut [u16],
) -> Result<(), BusError> {
    match register_data(request, pdu) {
        Some(bytes) => Registers { bytes }.copy_to(out),
        None => decode_registers_slowly(request, pdu, out),
    }
}

/// Everything [`decode_registers`] does not accept at first sight: exceptions, malformed or
/// mismatched answers, requests that are not register reads. Out of line to keep the fast path
/// small. It is the general route — [`decode_response`], then [`Registers::copy_to`] — which the
/// tests hold the fast path to.
#[cold]
#[inline(never)]
pub(super) fn decode_registers_slowly(
    request: &Request<'_>,
    pdu: &[u8],
    out: &mut [u16],
) -> Result<(), BusError> {
    match decode_response(request, pdu)? {
        Response::Registers(registers) => registers.copy_to(out),
        _ => Err(frame_error("response does not match the request")),
    }
}

/// The register bytes of `pdu` if it is a well-formed normal answer to register read `request`
/// (function code, byte count and length all match); `None` for anything else, which the general
/// decoder then classifies. Small enough to inline into every caller.
#[inline]
fn register_data<'a>(request: &Request<'_>, pdu: &'a [u8]) -> Option<&'a [u8]> {
    let (head, len) = request.register_answer()?;
    if pdu.len() != len {
        return None;
    }
    let (first, data) = pdu.split_first_chunk()?;
    (*first == head).then_some(data)
}

fn decode_any_response<'a>(request: &Request<'_>, pdu: &'a [u8]) -> Result<Response<'a>, BusError> {
    let function = request.function();
    let (&got, body) = pdu.split_first().ok_or(frame_error("empty response PDU"))?;
    if function::is_exception(got) {
        return match body {
            [code] => Err(BusError::ModbusException {
                function,
                code: ExceptionCode::from(*code),
            }),
            _ => Err(frame_error("exception response has the wrong length")),
        };
    }
    if got != function {
        return Err(frame_error("function code does not match the request"));
    }
    if pdu.len() != request.response_len() {
        return Err(frame_error("response length does not match the request"));
    }
    match *request {
        Request::ReadCoils { count, .. } | Request::ReadDiscreteInputs { count, .. } => {
            check_byte_count(body)?;
            Ok(Response::Bits(Bits::new(&body[1..], count as usize)))
        }
        Request::ReadHoldingRegisters { .. } | Request::ReadInputRegisters { .. } => {
            check_byte_count(body)?;
            Ok(Response::Registers(Registers::new(&body[1..])))
        }
        _ => {
            let mut expected = [0u8; 5];
            let (start, count) = request.span();
            expected[1..3].copy_from_slice(&start.to_be_bytes());
            let second = match *request {
                Request::WriteSingleCoil { value, .. } => {
                    if value {
                        COIL_ON
                    } else {
                        COIL_OFF
                    }
                }
                Request::WriteSingleRegister { value, .. } => value,
                _ => count as u16,
            };
            expected[3..5].copy_from_slice(&second.to_be_bytes());
            if pdu[1..] != expected[1..] {
                return Err(frame_error("write echo does not match the request"));
            }
            Ok(Response::Written)
        }
    }
}

/// The byte count is redundant with the request's count (already checked through the length).
#[inline]
fn check_byte_count(body: &[u8]) -> Result<(), BusError> {
    if body[0] as usize != body.len() - 1 {
        return Err(frame_error("byte count does not match the request"));
    }
    Ok(())
}

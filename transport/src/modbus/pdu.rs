//! Modbus PDUs: request encoding, response decoding (checked against the request), and the server
//! side of both for simulators and tests.
//!
//! Everything works on caller-provided slices: nothing allocates, and no input makes a decoder
//! panic — a malformed PDU is a [`BusError::Frame`], an exception response a
//! [`BusError::ModbusException`].

use crate::error::BusError;

use super::address::Table;

/// Function codes this crate speaks.
pub mod function {
    /// Read coils.
    pub const READ_COILS: u8 = 0x01;
    /// Read discrete inputs.
    pub const READ_DISCRETE_INPUTS: u8 = 0x02;
    /// Read holding registers.
    pub const READ_HOLDING_REGISTERS: u8 = 0x03;
    /// Read input registers.
    pub const READ_INPUT_REGISTERS: u8 = 0x04;
    /// Write single coil.
    pub const WRITE_SINGLE_COIL: u8 = 0x05;
    /// Write single register.
    pub const WRITE_SINGLE_REGISTER: u8 = 0x06;
    /// Write multiple coils.
    pub const WRITE_MULTIPLE_COILS: u8 = 0x0F;
    /// Write multiple registers.
    pub const WRITE_MULTIPLE_REGISTERS: u8 = 0x10;
    /// Set on the function code of an exception response.
    pub const EXCEPTION_FLAG: u8 = 0x80;

    /// Whether function code `got` answers a request as an exception: the standard
    /// `request | 0x80`, or any code with bit 7 set — some devices answer under another one (the
    /// Kinco FD manual shows 0x81 for FC 0x03, line 2424), and no normal answer has bit 7 set.
    #[inline]
    pub const fn is_exception(got: u8) -> bool {
        got & EXCEPTION_FLAG != 0
    }
}

/// Largest PDU the specification allows (256-byte RTU ADU minus address and CRC).
pub const MAX_PDU: usize = 253;
/// Most registers one read may ask for.
pub const MAX_READ_REGISTERS: u16 = 125;
/// Most registers one FC 0x10 write may carry.
pub const MAX_WRITE_REGISTERS: u16 = 123;
/// Most bits one FC 0x01 / 0x02 read may ask for.
pub const MAX_READ_BITS: u16 = 2000;
/// Most coils one FC 0x0F write may carry.
pub const MAX_WRITE_BITS: u16 = 1968;

const COIL_ON: u16 = 0xFF00;
const COIL_OFF: u16 = 0x0000;

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

#[inline]
fn frame_error(why: &'static str) -> BusError {
    BusError::Frame(why)
}

/// Checks that `count` items starting at `start` are within `1..=max` and the 16-bit address space.
#[inline]
fn check_span(start: u16, count: usize, max: u16) -> Result<(), BusError> {
    if count == 0 || count > max as usize {
        return Err(BusError::Unsupported(
            "item count outside the Modbus limits",
        ));
    }
    if start as usize + count > 0x1_0000 {
        return Err(BusError::Unsupported("request runs past address 0xFFFF"));
    }
    Ok(())
}

#[inline]
const fn bit_bytes(count: usize) -> usize {
    count.div_ceil(8)
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

fn pack_bits(values: &[bool], out: &mut [u8]) {
    for (byte, bits) in out.iter_mut().zip(values.chunks(8)) {
        *byte = bits
            .iter()
            .enumerate()
            .fold(0u8, |acc, (i, &bit)| acc | ((bit as u8) << i));
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

#[inline]
fn be16(bytes: &[u8], at: usize) -> u16 {
    u16::from_be_bytes([bytes[at], bytes[at + 1]])
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
fn decode_registers_slowly(
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
                code: *code,
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

/// A request as a server sees it: like [`Request`], with write payloads still in wire form.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ServerRequest<'a> {
    /// FC 0x01 / 0x02 / 0x03 / 0x04: `count` items from `start`.
    Read {
        /// Function code.
        function: u8,
        /// First address.
        start: u16,
        /// Item count.
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
        /// New states.
        values: Bits<'a>,
    },
    /// FC 0x10.
    WriteMultipleRegisters {
        /// First register.
        start: u16,
        /// New values.
        values: Registers<'a>,
    },
}

/// Decodes a request PDU (server side); every malformed PDU is a [`BusError::Frame`], an unknown
/// function code [`BusError::Unsupported`].
#[inline]
pub fn decode_request(pdu: &[u8]) -> Result<ServerRequest<'_>, BusError> {
    let (&function, _) = pdu.split_first().ok_or(frame_error("empty request PDU"))?;
    if pdu.len() < 5 {
        return Err(frame_error("request PDU too short"));
    }
    let (first, second) = (be16(pdu, 1), be16(pdu, 3));
    let fixed = |request| {
        if pdu.len() == 5 {
            Ok(request)
        } else {
            Err(frame_error("request PDU has the wrong length"))
        }
    };
    let request = match function {
        function::READ_COILS | function::READ_DISCRETE_INPUTS => {
            check_span(first, second as usize, MAX_READ_BITS)?;
            fixed(ServerRequest::Read {
                function,
                start: first,
                count: second,
            })?
        }
        function::READ_HOLDING_REGISTERS | function::READ_INPUT_REGISTERS => {
            check_span(first, second as usize, MAX_READ_REGISTERS)?;
            fixed(ServerRequest::Read {
                function,
                start: first,
                count: second,
            })?
        }
        function::WRITE_SINGLE_COIL => fixed(ServerRequest::WriteSingleCoil {
            address: first,
            value: match second {
                COIL_ON => true,
                COIL_OFF => false,
                _ => return Err(frame_error("coil value is neither 0xFF00 nor 0x0000")),
            },
        })?,
        function::WRITE_SINGLE_REGISTER => fixed(ServerRequest::WriteSingleRegister {
            address: first,
            value: second,
        })?,
        function::WRITE_MULTIPLE_COILS | function::WRITE_MULTIPLE_REGISTERS => {
            let coils = function == function::WRITE_MULTIPLE_COILS;
            let (max, bytes) = if coils {
                (MAX_WRITE_BITS, bit_bytes(second as usize))
            } else {
                (MAX_WRITE_REGISTERS, 2 * second as usize)
            };
            check_span(first, second as usize, max)?;
            let data = pdu.get(6..).ok_or(frame_error("request PDU too short"))?;
            if pdu[5] as usize != bytes || data.len() != bytes {
                return Err(frame_error("byte count does not match the item count"));
            }
            if coils {
                ServerRequest::WriteMultipleCoils {
                    start: first,
                    values: Bits::new(data, second as usize),
                }
            } else {
                ServerRequest::WriteMultipleRegisters {
                    start: first,
                    values: Registers::new(data),
                }
            }
        }
        _ => return Err(BusError::Unsupported("function code not implemented")),
    };
    Ok(request)
}

/// Encodes a register read response (FC 0x03 / 0x04) into `out`; returns its length.
#[inline]
pub fn encode_registers_response(
    function: u8,
    values: &[u16],
    out: &mut [u8],
) -> Result<usize, BusError> {
    check_span(0, values.len(), MAX_READ_REGISTERS)?;
    let len = 2 + 2 * values.len();
    let out = out.get_mut(..len).ok_or(BusError::Unsupported(
        "output buffer too small for the response",
    ))?;
    out[0] = function;
    out[1] = (2 * values.len()) as u8;
    for (chunk, value) in out[2..].chunks_exact_mut(2).zip(values) {
        chunk.copy_from_slice(&value.to_be_bytes());
    }
    Ok(len)
}

/// Encodes a bit read response (FC 0x01 / 0x02) into `out`; returns its length.
#[inline]
pub fn encode_bits_response(
    function: u8,
    values: &[bool],
    out: &mut [u8],
) -> Result<usize, BusError> {
    check_span(0, values.len(), MAX_READ_BITS)?;
    let bytes = bit_bytes(values.len());
    let out = out.get_mut(..2 + bytes).ok_or(BusError::Unsupported(
        "output buffer too small for the response",
    ))?;
    out[0] = function;
    out[1] = bytes as u8;
    pack_bits(values, &mut out[2..]);
    Ok(2 + bytes)
}

/// Encodes the response confirming a write request `pdu` (the echo of its first five bytes).
#[inline]
pub fn encode_write_response(request_pdu: &[u8], out: &mut [u8]) -> Result<usize, BusError> {
    let echo = request_pdu
        .get(..5)
        .ok_or(frame_error("request PDU too short"))?;
    out.get_mut(..5)
        .ok_or(BusError::Unsupported(
            "output buffer too small for the response",
        ))?
        .copy_from_slice(echo);
    Ok(5)
}

/// Encodes an exception response into `out`; returns its length (2).
#[inline]
pub fn encode_exception(function: u8, code: u8, out: &mut [u8]) -> Result<usize, BusError> {
    let out = out.get_mut(..2).ok_or(BusError::Unsupported(
        "output buffer too small for the response",
    ))?;
    out[0] = function | function::EXCEPTION_FLAG;
    out[1] = code;
    Ok(2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::vec::Vec;

    fn encoded(request: &Request<'_>) -> Vec<u8> {
        let mut out = [0u8; MAX_PDU];
        let len = request.encode(&mut out).unwrap();
        out[..len].to_vec()
    }

    #[test]
    fn encodes_the_manuals_requests() {
        let write = Request::WriteSingleRegister {
            address: 0x0028,
            value: 2,
        };
        assert_eq!(encoded(&write), [0x06, 0x00, 0x28, 0x00, 0x02]);
        let read = Request::ReadInputRegisters {
            start: 0x0060,
            count: 17,
        };
        assert_eq!(encoded(&read), [0x04, 0x00, 0x60, 0x00, 0x11]);
        let coils = Request::WriteMultipleCoils {
            start: 0x13,
            values: &[
                true, false, true, true, false, false, true, true, true, false,
            ],
        };
        // The specification's own example: 10 coils from 20 (0x13) = CD 01.
        assert_eq!(
            encoded(&coils),
            [0x0F, 0x00, 0x13, 0x00, 0x0A, 0x02, 0xCD, 0x01]
        );
        let regs = Request::WriteMultipleRegisters {
            start: 1,
            values: &[0x000A, 0x0102],
        };
        assert_eq!(
            encoded(&regs),
            [0x10, 0, 1, 0, 2, 4, 0x00, 0x0A, 0x01, 0x02]
        );
    }

    #[test]
    fn rejects_out_of_spec_requests_before_sending() {
        let mut out = [0u8; MAX_PDU];
        for request in [
            Request::ReadHoldingRegisters { start: 0, count: 0 },
            Request::ReadHoldingRegisters {
                start: 0,
                count: 126,
            },
            Request::ReadCoils {
                start: 0,
                count: 2001,
            },
            Request::ReadInputRegisters {
                start: 0xFFFF,
                count: 2,
            },
            Request::WriteMultipleRegisters {
                start: 0,
                values: &[0; 124],
            },
        ] {
            assert!(matches!(
                request.encode(&mut out),
                Err(BusError::Unsupported(_))
            ));
        }
        let short = &mut [0u8; 4];
        let read = Request::ReadHoldingRegisters { start: 0, count: 1 };
        assert!(read.encode(short).is_err());
    }

    #[test]
    fn decodes_responses_and_rejects_what_does_not_match() {
        let read = Request::ReadHoldingRegisters {
            start: 0x3C,
            count: 2,
        };
        let Ok(Response::Registers(regs)) = decode_response(&read, &[3, 4, 0x12, 0x34, 0xAB, 0xCD])
        else {
            panic!("valid response rejected");
        };
        assert_eq!(regs.iter().collect::<Vec<_>>(), [0x1234, 0xABCD]);
        let cases: [(&[u8], &str); 5] = [
            (
                &[4, 4, 0, 0, 0, 0],
                "function code does not match the request",
            ),
            (&[3, 2, 0, 0], "response length does not match the request"),
            (&[3, 6, 0, 0, 0, 0], "byte count does not match the request"),
            (&[], "empty response PDU"),
            (&[0x83, 2, 0], "exception response has the wrong length"),
        ];
        for (pdu, why) in cases {
            assert_eq!(decode_response(&read, pdu), Err(BusError::Frame(why)));
        }
        assert_eq!(
            decode_response(&read, &[0x83, 0x02]),
            Err(BusError::ModbusException {
                function: 3,
                code: 2
            })
        );
        // Kinco FD manual line 2424: the exception to FC 0x03 comes back as 0x81.
        assert_eq!(
            decode_response(&read, &[0x81, 0x02]),
            Err(BusError::ModbusException {
                function: 3,
                code: 2
            })
        );
        let write = Request::WriteSingleRegister {
            address: 0x28,
            value: 2,
        };
        assert_eq!(
            decode_response(&write, &[6, 0, 0x28, 0, 2]),
            Ok(Response::Written)
        );
        assert_eq!(
            decode_response(&write, &[6, 0, 0x28, 0, 3]),
            Err(BusError::Frame("write echo does not match the request"))
        );
    }

    fn any_request() -> impl Strategy<Value = (u8, u16, Vec<u16>, Vec<bool>)> {
        (
            0u8..8,
            any::<u16>(),
            proptest::collection::vec(any::<u16>(), 1..=123),
            proptest::collection::vec(any::<bool>(), 1..=300),
        )
    }

    fn build<'a>(kind: u8, start: u16, regs: &'a [u16], bits: &'a [bool]) -> Request<'a> {
        let count = regs.len() as u16;
        match kind {
            0 => Request::ReadCoils {
                start,
                count: bits.len() as u16,
            },
            1 => Request::ReadDiscreteInputs {
                start,
                count: bits.len() as u16,
            },
            2 => Request::ReadHoldingRegisters { start, count },
            3 => Request::ReadInputRegisters { start, count },
            4 => Request::WriteSingleCoil {
                address: start,
                value: bits[0],
            },
            5 => Request::WriteSingleRegister {
                address: start,
                value: regs[0],
            },
            6 => Request::WriteMultipleCoils {
                start,
                values: bits,
            },
            _ => Request::WriteMultipleRegisters {
                start,
                values: regs,
            },
        }
    }

    #[test]
    fn decodes_registers_in_one_pass_with_the_general_errors() {
        let read = Request::ReadInputRegisters { start: 0, count: 2 };
        let mut out = [0u16; 2];
        decode_registers(&read, &[4, 4, 0x12, 0x34, 0xAB, 0xCD], &mut out).unwrap();
        assert_eq!(out, [0x1234, 0xABCD]);
        let cases: [(&[u8], BusError); 4] = [
            (
                &[0x84, 2],
                BusError::ModbusException {
                    function: 4,
                    code: 2,
                },
            ),
            (
                &[3, 4, 0, 0, 0, 0],
                frame_error("function code does not match the request"),
            ),
            (
                &[4, 5, 0, 0, 0, 0],
                frame_error("byte count does not match the request"),
            ),
            (
                &[4, 4, 0, 0],
                frame_error("response length does not match the request"),
            ),
        ];
        for (pdu, error) in cases {
            assert_eq!(decode_registers(&read, pdu, &mut out), Err(error));
        }
        assert_eq!(out, [0x1234, 0xABCD], "rejected answers leave `out` alone");
        assert_eq!(
            decode_registers(&read, &[4, 4, 0, 0, 0, 0], &mut [0u16; 3]),
            Err(frame_error("register count does not match the request"))
        );
        let write = Request::WriteSingleRegister {
            address: 0x28,
            value: 2,
        };
        assert_eq!(
            decode_registers(&write, &[6, 0, 0x28, 0, 2], &mut out),
            Err(frame_error("response does not match the request"))
        );
    }

    #[test]
    fn register_answers_follow_from_the_request() {
        let read = |count| Request::ReadHoldingRegisters { start: 0, count };
        assert_eq!(read(1).register_answer(), Some(([3, 2], 4)));
        assert_eq!(read(125).register_answer(), Some(([3, 250], 252)));
        assert_eq!(read(127).register_answer(), Some(([3, 254], 256)));
        // No byte count can say 256 or more: no answer can match.
        assert_eq!(read(128).register_answer(), None);
        assert_eq!(read(u16::MAX).register_answer(), None);
        let coils = Request::ReadCoils { start: 0, count: 8 };
        assert_eq!(coils.register_answer(), None);
    }

    proptest! {
        #[test]
        fn request_and_response_round_trip((kind, start, regs, bits) in any_request()) {
            let request = build(kind, start, &regs, &bits);
            let mut pdu = [0u8; MAX_PDU];
            let Ok(len) = request.encode(&mut pdu) else {
                // Only requests running past 0xFFFF are refused.
                let (start, count) = request.span();
                prop_assert!(start as usize + count > 0x1_0000);
                return Ok(());
            };
            prop_assert_eq!(len, request.encoded_len());
            let server = decode_request(&pdu[..len]).unwrap();
            let mut reply = [0u8; MAX_PDU];
            let reply_len = match server {
                ServerRequest::Read { function, count, .. } if function <= 2 => {
                    encode_bits_response(function, &bits[..count as usize], &mut reply)
                }
                ServerRequest::Read { function, count, .. } => {
                    encode_registers_response(function, &regs[..count as usize], &mut reply)
                }
                ServerRequest::WriteMultipleCoils { values, .. } => {
                    let mut back = std::vec![false; values.len()];
                    values.copy_to(&mut back).unwrap();
                    prop_assert_eq!(&back[..], &bits[..]);
                    encode_write_response(&pdu[..len], &mut reply)
                }
                ServerRequest::WriteMultipleRegisters { values, .. } => {
                    prop_assert_eq!(values.iter().collect::<Vec<_>>(), regs.clone());
                    encode_write_response(&pdu[..len], &mut reply)
                }
                _ => encode_write_response(&pdu[..len], &mut reply),
            }
            .unwrap();
            prop_assert_eq!(reply_len, request.response_len());
            match decode_response(&request, &reply[..reply_len]).unwrap() {
                Response::Registers(got) => {
                    let mut out = std::vec![0u16; got.len()];
                    got.copy_to(&mut out).unwrap();
                    prop_assert_eq!(&out[..], &regs[..]);
                }
                Response::Bits(got) => {
                    let mut out = std::vec![false; got.len()];
                    got.copy_to(&mut out).unwrap();
                    prop_assert_eq!(&out[..], &bits[..]);
                }
                Response::Written => prop_assert!(request.is_write()),
            }
        }

        #[test]
        fn decoders_never_panic_on_arbitrary_bytes(
            (kind, start, regs, bits) in any_request(),
            bytes in proptest::collection::vec(any::<u8>(), 0..300),
        ) {
            let request = build(kind, start, &regs, &bits);
            if let Ok(Response::Registers(got)) = decode_response(&request, &bytes) {
                prop_assert_eq!(got.len(), request.span().1);
            }
            let _ = decode_request(&bytes);
        }

        #[test]
        fn decode_registers_agrees_with_the_general_decoder(
            (kind, start, regs, bits) in any_request(),
            bytes in proptest::collection::vec(any::<u8>(), 0..300),
            slots in 0usize..130,
        ) {
            let request = build(kind, start, &regs, &bits);
            let (mut fast, mut general) = (std::vec![0u16; slots], std::vec![0u16; slots]);
            let got = decode_registers(&request, &bytes, &mut fast);
            prop_assert_eq!(&got, &decode_registers_slowly(&request, &bytes, &mut general));
            prop_assert_eq!(fast, general);
        }

        #[test]
        fn decode_registers_agrees_on_damaged_answers(
            values in proptest::collection::vec(any::<u16>(), 1..=125),
            other_count in proptest::option::of(1u16..=127),
            flip in proptest::option::of((any::<prop::sample::Index>(), 1u8..)),
            cut in proptest::option::of(any::<prop::sample::Index>()),
        ) {
            let count = other_count.unwrap_or(values.len() as u16);
            let request = Request::ReadInputRegisters { start: 0, count };
            let mut pdu = [0u8; MAX_PDU];
            let mut len = encode_registers_response(4, &values, &mut pdu).unwrap();
            if let Some((at, bits)) = flip {
                pdu[at.index(len)] ^= bits;
            }
            if let Some(at) = cut {
                len = at.index(len);
            }
            let (mut fast, mut general) = (std::vec![0u16; values.len()], std::vec![0u16; values.len()]);
            let got = decode_registers(&request, &pdu[..len], &mut fast);
            prop_assert_eq!(&got, &decode_registers_slowly(&request, &pdu[..len], &mut general));
            prop_assert_eq!(&fast, &general);
            if flip.is_none() && cut.is_none() && usize::from(count) == values.len() {
                prop_assert_eq!(got, Ok(()));
                prop_assert_eq!(fast, values);
            }
        }
    }
}

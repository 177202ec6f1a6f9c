//! The server side: request PDUs decoded into the [`Request`] a client sent, and responses
//! encoded.

use crate::error::BusError;

use super::*;

/// Decodes a request PDU (server side); every malformed PDU is a [`BusError::Frame`], an unknown
/// function code [`BusError::Unsupported`].
#[inline]
pub fn decode_request(pdu: &[u8]) -> Result<Request<'_>, BusError> {
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
        function::READ_COILS
        | function::READ_DISCRETE_INPUTS
        | function::READ_HOLDING_REGISTERS
        | function::READ_INPUT_REGISTERS => fixed(read(function, first, second)?)?,
        function::WRITE_SINGLE_COIL => fixed(Request::WriteSingleCoil {
            address: first,
            value: match second {
                COIL_ON => true,
                COIL_OFF => false,
                _ => return Err(frame_error("coil value is neither 0xFF00 nor 0x0000")),
            },
        })?,
        function::WRITE_SINGLE_REGISTER => fixed(Request::WriteSingleRegister {
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
                Request::WriteMultipleCoils {
                    start: first,
                    values: Bits::new(data, second as usize),
                }
            } else {
                Request::WriteMultipleRegisters {
                    start: first,
                    values: Registers::new(data),
                }
            }
        }
        _ => return Err(BusError::Unsupported("function code not implemented")),
    };
    Ok(request)
}

/// The read request of read function code `function` for `count` items from `start`, refused
/// outside the limits of its kind.
fn read(function: u8, start: u16, count: u16) -> Result<Request<'static>, BusError> {
    let request = match function {
        function::READ_COILS => Request::ReadCoils { start, count },
        function::READ_DISCRETE_INPUTS => Request::ReadDiscreteInputs { start, count },
        function::READ_HOLDING_REGISTERS => Request::ReadHoldingRegisters { start, count },
        _ => Request::ReadInputRegisters { start, count },
    };
    request.validate()?;
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

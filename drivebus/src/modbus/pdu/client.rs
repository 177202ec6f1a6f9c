//! The client side: response PDUs decoded against the request they answer.

use crate::error::BusError;
use crate::modbus::exception::ExceptionCode;

use super::*;

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
        Some(bytes) => Ok(Response::Registers(Registers::new(bytes))),
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
        Some(bytes) => Registers::new(bytes).copy_to(out),
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

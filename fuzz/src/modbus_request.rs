//! A Modbus client request from five bytes: `[kind, start (2 bytes, big-endian), count or value
//! (2 bytes)]`. `kind % 8` picks the function in the order of [`Request`]'s variants; write
//! payloads are zeros of the given count (an answer echoes only the start and count).

use drivebus::modbus::pdu::{Request, MAX_WRITE_BITS, MAX_WRITE_REGISTERS};

use crate::Cursor;

/// Payload of multiple-coil writes: only its length matters to the answer.
static COILS: [bool; MAX_WRITE_BITS as usize] = [false; MAX_WRITE_BITS as usize];
/// Payload of multiple-register writes.
static REGISTERS: [u16; MAX_WRITE_REGISTERS as usize] = [0; MAX_WRITE_REGISTERS as usize];

/// The request the next five bytes of `input` describe; `None` if the client would refuse to
/// send it ([`Request::validate`]).
pub fn read(input: &mut Cursor<'_>) -> Option<Request<'static>> {
    let kind = input.u8() % 8;
    let start = input.u16();
    let count = input.u16();
    let request = match kind {
        0 => Request::ReadCoils { start, count },
        1 => Request::ReadDiscreteInputs { start, count },
        2 => Request::ReadHoldingRegisters { start, count },
        3 => Request::ReadInputRegisters { start, count },
        4 => Request::WriteSingleCoil {
            address: start,
            value: count != 0,
        },
        5 => Request::WriteSingleRegister {
            address: start,
            value: count,
        },
        6 => Request::write_coils(start, &COILS[..usize::from(count).min(COILS.len())]),
        _ => Request::write_registers(
            start,
            &REGISTERS[..usize::from(count).min(REGISTERS.len())],
        ),
    };
    request.validate().ok().map(|()| request)
}

//! Modbus PDUs. One [`Request`] type for both sides (`pdu/request.rs`: what a client encodes, what
//! a server decodes), carrying [`Registers`] and [`Bits`] (`pdu/values.rs`); the client's response
//! decoding, checked against the request, in `pdu/client.rs`; the server's request decoding and
//! response encoding in `pdu/server.rs` (feature `server`); function codes, limits and field
//! helpers shared by all of them here.
//!
//! Everything works on caller-provided slices: nothing allocates, and no input makes a decoder
//! panic — a malformed PDU is a [`BusError::Frame`], an exception response a
//! [`BusError::ModbusException`].

use crate::error::BusError;

mod client;
mod request;
#[cfg(feature = "server")]
mod server;
#[cfg(test)]
mod tests;
mod values;

pub use client::{decode_registers, decode_response, Response};
pub use request::Request;
#[cfg(feature = "server")]
pub use server::{
    decode_request, encode_bits_response, encode_exception, encode_registers_response,
    encode_write_response,
};
pub use values::{Bits, Registers};

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

pub(crate) const COIL_ON: u16 = 0xFF00;
pub(crate) const COIL_OFF: u16 = 0x0000;

#[inline]
pub(crate) fn frame_error(why: &'static str) -> BusError {
    BusError::Frame(why)
}

/// Checks that `count` items starting at `start` are within `1..=max` and the 16-bit address space.
#[inline]
pub(crate) fn check_span(start: u16, count: usize, max: u16) -> Result<(), BusError> {
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
pub(crate) const fn bit_bytes(count: usize) -> usize {
    count.div_ceil(8)
}

pub(crate) fn pack_bits(values: &[bool], out: &mut [u8]) {
    for (byte, bits) in out.iter_mut().zip(values.chunks(8)) {
        *byte = bits
            .iter()
            .enumerate()
            .fold(0u8, |acc, (i, &bit)| acc | ((bit as u8) << i));
    }
}

#[cfg(feature = "server")]
#[inline]
pub(crate) fn be16(bytes: &[u8], at: usize) -> u16 {
    u16::from_be_bytes([bytes[at], bytes[at + 1]])
}

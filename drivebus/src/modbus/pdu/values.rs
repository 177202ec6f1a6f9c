//! The values a PDU carries: registers and bits, borrowed either from a frame (still in wire form)
//! or from the caller (a client's write). One type for both, so a request has the same type
//! whether a client builds it or a server decodes it, and no side copies values to change form.

use core::fmt;

use crate::error::BusError;

use super::{bit_bytes, frame_error, pack_bits};

/// What both runs share: built from the caller's slice, compared by value (whatever their form),
/// printed as their values.
macro_rules! value_run {
    ($run:ident, $value:ty) => {
        impl<'a> From<&'a [$value]> for $run<'a> {
            fn from(values: &'a [$value]) -> Self {
                Self::from_values(values)
            }
        }

        impl PartialEq for $run<'_> {
            fn eq(&self, other: &Self) -> bool {
                self.len() == other.len() && self.iter().eq(other.iter())
            }
        }

        impl Eq for $run<'_> {}

        impl fmt::Debug for $run<'_> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.debug_list().entries(self.iter()).finish()
            }
        }
    };
}

/// A run of register values: borrowed from a frame in wire (big-endian) form (a read answer, a
/// decoded write request) or from the caller's `&[u16]` (a write a client sends).
///
/// Two runs are equal when they hold the same values, whichever form they are in.
#[derive(Clone, Copy)]
pub struct Registers<'a> {
    form: RegisterForm<'a>,
}

#[derive(Clone, Copy)]
enum RegisterForm<'a> {
    /// Big-endian pairs of bytes, as on the wire.
    Wire(&'a [u8]),
    /// Values in native form.
    Values(&'a [u16]),
}

impl<'a> Registers<'a> {
    /// Views big-endian register bytes; an odd trailing byte is ignored.
    #[inline]
    pub fn new(bytes: &'a [u8]) -> Self {
        Self {
            form: RegisterForm::Wire(&bytes[..bytes.len() & !1]),
        }
    }
    /// Views register values the caller holds (the payload of a write).
    #[inline]
    pub const fn from_values(values: &'a [u16]) -> Self {
        Self {
            form: RegisterForm::Values(values),
        }
    }
    /// Number of registers.
    #[inline]
    pub fn len(&self) -> usize {
        match self.form {
            RegisterForm::Wire(bytes) => bytes.len() / 2,
            RegisterForm::Values(values) => values.len(),
        }
    }
    /// Whether there are none.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Register `i`, if present.
    #[inline]
    pub fn get(&self, i: usize) -> Option<u16> {
        match self.form {
            RegisterForm::Wire(bytes) => {
                let pair = bytes.get(2 * i..2 * i + 2)?;
                Some(u16::from_be_bytes([pair[0], pair[1]]))
            }
            RegisterForm::Values(values) => values.get(i).copied(),
        }
    }
    /// The registers in address order.
    #[inline]
    pub fn iter(&self) -> impl Iterator<Item = u16> + 'a {
        let (bytes, values): (&'a [u8], &'a [u16]) = match self.form {
            RegisterForm::Wire(bytes) => (bytes, &[]),
            RegisterForm::Values(values) => (&[], values),
        };
        // One of the two is empty: chaining them avoids an iterator type per form.
        bytes
            .chunks_exact(2)
            .map(|pair| u16::from_be_bytes([pair[0], pair[1]]))
            .chain(values.iter().copied())
    }
    /// Copies the registers into `out`, which must have exactly [`len`](Self::len) slots.
    #[inline]
    pub fn copy_to(&self, out: &mut [u16]) -> Result<(), BusError> {
        if out.len() != self.len() {
            return Err(frame_error("register count does not match the request"));
        }
        match self.form {
            RegisterForm::Wire(bytes) => {
                for (slot, pair) in out.iter_mut().zip(bytes.chunks_exact(2)) {
                    *slot = u16::from_be_bytes([pair[0], pair[1]]);
                }
            }
            RegisterForm::Values(values) => out.copy_from_slice(values),
        }
        Ok(())
    }
    /// Writes the registers big-endian into `out`, which must have room for them.
    #[inline]
    pub(super) fn write_wire(&self, out: &mut [u8]) {
        match self.form {
            RegisterForm::Wire(bytes) => out[..bytes.len()].copy_from_slice(bytes),
            RegisterForm::Values(values) => {
                for (chunk, value) in out.chunks_exact_mut(2).zip(values) {
                    chunk.copy_from_slice(&value.to_be_bytes());
                }
            }
        }
    }
}

value_run!(Registers, u16);

/// A run of bits (coils or discrete inputs): borrowed from a frame, packed LSB first (a read
/// answer, a decoded write request), or from the caller's `&[bool]` (a write a client sends).
///
/// Two runs are equal when they hold the same bits, whichever form they are in.
#[derive(Clone, Copy)]
pub struct Bits<'a> {
    form: BitForm<'a>,
}

#[derive(Clone, Copy)]
enum BitForm<'a> {
    /// `count` bits packed LSB first, as on the wire.
    Wire { bytes: &'a [u8], count: usize },
    /// Bits in native form.
    Values(&'a [bool]),
}

impl<'a> Bits<'a> {
    /// Views `count` packed bits (fewer if `bytes` is short).
    #[inline]
    pub fn new(bytes: &'a [u8], count: usize) -> Self {
        Self {
            form: BitForm::Wire {
                bytes,
                count: count.min(bytes.len() * 8),
            },
        }
    }
    /// Views bits the caller holds (the payload of a write).
    #[inline]
    pub const fn from_values(values: &'a [bool]) -> Self {
        Self {
            form: BitForm::Values(values),
        }
    }
    /// Number of bits.
    #[inline]
    pub fn len(&self) -> usize {
        match self.form {
            BitForm::Wire { count, .. } => count,
            BitForm::Values(values) => values.len(),
        }
    }
    /// Whether there are none.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Bit `i`, if present.
    #[inline]
    pub fn get(&self, i: usize) -> Option<bool> {
        match self.form {
            BitForm::Wire { bytes, count } => {
                (i < count).then(|| bytes[i / 8] & (1 << (i % 8)) != 0)
            }
            BitForm::Values(values) => values.get(i).copied(),
        }
    }
    /// The bits in address order.
    #[inline]
    pub fn iter(&self) -> impl Iterator<Item = bool> + 'a {
        let bits = *self;
        (0..bits.len()).filter_map(move |i| bits.get(i))
    }
    /// Copies the bits into `out`, which must have exactly [`len`](Self::len) slots.
    #[inline]
    pub fn copy_to(&self, out: &mut [bool]) -> Result<(), BusError> {
        if out.len() != self.len() {
            return Err(frame_error("bit count does not match the request"));
        }
        for (slot, bit) in out.iter_mut().zip(self.iter()) {
            *slot = bit;
        }
        Ok(())
    }
    /// Packs the bits LSB first into `out`, which must have room for them; the unused bits of the
    /// last byte are zero.
    #[inline]
    pub(super) fn write_wire(&self, out: &mut [u8]) {
        match self.form {
            BitForm::Wire { bytes, count } => {
                let len = bit_bytes(count);
                out[..len].copy_from_slice(&bytes[..len]);
                if count % 8 != 0 {
                    out[len - 1] &= 0xFF >> (8 - count % 8);
                }
            }
            BitForm::Values(values) => pack_bits(values, out),
        }
    }
}

value_run!(Bits, bool);

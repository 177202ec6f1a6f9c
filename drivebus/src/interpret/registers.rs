//! Parameter values ↔ Modbus registers, for any IR type: integers are sign-extended into and
//! range-checked out of their registers, other types are copied byte for byte.

use core::fmt;
use std::vec;
use std::vec::Vec;

use super::raw;
use crate::modbus::{le_to_registers, registers_to_le, WordOrder};
use crate::DataType;

/// Why registers do not hold a value of the parameter's type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unfit {
    /// An integer above the type's largest value.
    TooHigh,
    /// An integer below the type's smallest value.
    TooLow,
    /// More bytes than any integer type holds.
    WrongLength,
}

impl Unfit {
    /// Why, in words (also what [`BusError::Frame`](crate::BusError::Frame) carries for it).
    pub const fn reason(self) -> &'static str {
        match self {
            Self::TooHigh => "the drive answered a value above the parameter's type",
            Self::TooLow => "the drive answered a value below the parameter's type",
            Self::WrongLength => "the drive answered more bytes than any integer type holds",
        }
    }
}

impl fmt::Display for Unfit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.reason())
    }
}

/// The `width` little-endian wire bytes holding the little-endian value `bytes` of `data_type`:
/// integers sign- (or zero-) extended, other types copied and zero-padded.
pub fn to_wire(data_type: DataType, bytes: &[u8], width: usize) -> Vec<u8> {
    let mut wire = match raw::to_int(data_type, bytes) {
        Some(value) => value.to_le_bytes()[..width.min(16)].to_vec(),
        None => bytes.to_vec(),
    };
    wire.resize(width, 0);
    wire
}

/// The `words` registers (wire order) holding the little-endian value `bytes` of `data_type`.
pub fn to_registers(data_type: DataType, bytes: &[u8], words: u16, order: WordOrder) -> Vec<u16> {
    let wire = to_wire(data_type, bytes, 2 * words as usize);
    let mut regs = vec![0u16; words as usize];
    le_to_registers(&wire, order, &mut regs);
    regs
}

/// The little-endian value of `data_type` held in `regs` (wire order); an integer that does not
/// fit the type is refused.
pub fn from_registers(
    data_type: DataType,
    regs: &[u16],
    order: WordOrder,
) -> Result<Vec<u8>, Unfit> {
    let mut wire = vec![0u8; 2 * regs.len()];
    registers_to_le(regs, order, &mut wire);
    from_wire(data_type, wire)
}

/// The little-endian value of `data_type` in `wire`, the little-endian bytes of its registers
/// (what [`ModbusLink`](crate::modbus::ModbusLink) reads); an integer that does not fit the type is
/// refused.
pub fn from_wire(data_type: DataType, mut wire: Vec<u8>) -> Result<Vec<u8>, Unfit> {
    let Some((min, max)) = data_type.integer_bounds() else {
        wire.truncate(data_type.bytes() as usize);
        return Ok(wire);
    };
    let width = wire.len().min(16) as u8;
    let wire_type = match data_type {
        DataType::Signed(_) => DataType::Signed(width),
        _ => DataType::Unsigned(width),
    };
    let value = raw::to_int(wire_type, &wire).ok_or(Unfit::WrongLength)?;
    if value > max {
        return Err(Unfit::TooHigh);
    }
    if value < min {
        return Err(Unfit::TooLow);
    }
    Ok(raw::from_int(data_type, value))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signed_values_fill_their_registers() {
        let i16_type = DataType::Signed(2);
        assert_eq!(
            to_registers(i16_type, &(-3000i16).to_le_bytes(), 1, WordOrder::LowFirst),
            [0xF448]
        );
        assert_eq!(
            from_registers(i16_type, &[0xF448], WordOrder::LowFirst),
            Ok((-3000i16).to_le_bytes().to_vec())
        );
    }

    #[test]
    fn pairs_follow_the_word_order() {
        let u32_type = DataType::Unsigned(4);
        let bytes = 0x000F_4240u32.to_le_bytes();
        assert_eq!(
            to_registers(u32_type, &bytes, 2, WordOrder::LowFirst),
            [0x4240, 0x000F]
        );
        assert_eq!(
            to_registers(u32_type, &bytes, 2, WordOrder::HighFirst),
            [0x000F, 0x4240]
        );
        assert_eq!(
            from_registers(u32_type, &[0x000F, 0x4240], WordOrder::HighFirst),
            Ok(bytes.to_vec())
        );
    }

    #[test]
    fn integers_that_do_not_fit_are_refused() {
        assert_eq!(
            from_registers(DataType::Unsigned(1), &[0x0100], WordOrder::LowFirst),
            Err(Unfit::TooHigh)
        );
        assert_eq!(
            from_registers(DataType::Signed(1), &[0xFF7F], WordOrder::LowFirst),
            Err(Unfit::TooLow)
        );
    }
}

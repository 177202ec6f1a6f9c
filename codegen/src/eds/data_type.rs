//! CiA 301 data type codes (0x0001..=0x001B) and the IR types they map to.

use crate::ir::DataType;

/// Capacity given to strings and octet strings an EDS does not size: the runtime's maximum.
pub const UNSIZED_CAPACITY: u16 = drivebus_model::MAX_VALUE_BYTES as u16;

/// What a data type code means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Code {
    /// A type the IR models.
    Type(DataType),
    /// A code CiA 301 reserves (0x000E, 0x0017) or one beyond 0x001B.
    Unsupported,
}

/// The IR type of a CiA 301 data type code. Strings, octet strings and domains get `capacity`;
/// TIME_OF_DAY and TIME_DIFFERENCE are 6 raw octets.
pub fn from_code(code: u16, capacity: u16) -> Code {
    use DataType::*;
    Code::Type(match code {
        0x0001 => Bool,
        0x0002 => Signed(1),
        0x0003 => Signed(2),
        0x0004 => Signed(4),
        0x0005 => Unsigned(1),
        0x0006 => Unsigned(2),
        0x0007 => Unsigned(4),
        0x0008 => F32,
        0x0009 => String(capacity),
        0x000A | 0x000B | 0x000F => Octets(capacity),
        0x000C | 0x000D => Octets(6),
        0x0010 => Signed(3),
        0x0011 => F64,
        0x0012 => Signed(5),
        0x0013 => Signed(6),
        0x0014 => Signed(7),
        0x0015 => Signed(8),
        0x0016 => Unsigned(3),
        0x0018 => Unsigned(5),
        0x0019 => Unsigned(6),
        0x001A => Unsigned(7),
        0x001B => Unsigned(8),
        _ => return Code::Unsupported,
    })
}

/// The CiA 301 code of an IR type (octets export as OCTET_STRING).
pub fn to_code(ty: DataType) -> u16 {
    const SIGNED: [u16; 8] = [0x02, 0x03, 0x10, 0x04, 0x12, 0x13, 0x14, 0x15];
    const UNSIGNED: [u16; 8] = [0x05, 0x06, 0x16, 0x07, 0x18, 0x19, 0x1A, 0x1B];
    match ty {
        DataType::Bool => 0x01,
        DataType::Signed(b) => SIGNED[usize::from(b.clamp(1, 8) - 1)],
        DataType::Unsigned(b) => UNSIGNED[usize::from(b.clamp(1, 8) - 1)],
        DataType::F32 => 0x08,
        DataType::F64 => 0x11,
        DataType::String(_) => 0x09,
        DataType::Octets(_) => 0x0A,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_numeric_code_round_trips() {
        for code in (0x01..=0x1B).filter(|c| ![0x0B, 0x0C, 0x0D, 0x0E, 0x0F, 0x17].contains(c)) {
            let Code::Type(ty) = from_code(code, 8) else {
                panic!("code {code:#x} is supported");
            };
            assert_eq!(to_code(ty), code, "{ty:?}");
        }
        assert_eq!(from_code(0x0E, 8), Code::Unsupported);
        assert_eq!(from_code(0x17, 8), Code::Unsupported);
        assert_eq!(from_code(0x1C, 8), Code::Unsupported);
        assert_eq!(from_code(0x10, 8), Code::Type(DataType::Signed(3)));
    }
}

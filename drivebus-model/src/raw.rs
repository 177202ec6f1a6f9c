//! Raw values: the little-endian bytes a parameter holds, and the integers computed with them.

use alloc::vec;
use alloc::vec::Vec;

use crate::DataType;

/// The value of an integer (or bool) parameter held in `bytes`, sign-extended for signed types.
pub fn to_int(data_type: DataType, bytes: &[u8]) -> Option<i128> {
    let width = match data_type {
        DataType::Bool => 1,
        DataType::Unsigned(b) | DataType::Signed(b) => b as usize,
        _ => return None,
    };
    let mut buf = [0u8; 16];
    let n = width.min(bytes.len()).min(16);
    buf[..n].copy_from_slice(&bytes[..n]);
    let value = i128::from_le_bytes(buf);
    Some(match data_type {
        DataType::Signed(_) => {
            let shift = 128 - 8 * width as u32;
            (value << shift) >> shift
        }
        _ => value,
    })
}

/// The bytes of integer `value` in the width of `data_type` (two's complement, truncated).
pub fn from_int(data_type: DataType, value: i128) -> Vec<u8> {
    let width = data_type.bytes() as usize;
    value.to_le_bytes()[..width.min(16)].to_vec()
}

/// The value held in `bytes` as a float, for range checks of any numeric type.
pub fn to_f64(data_type: DataType, bytes: &[u8]) -> Option<f64> {
    match data_type {
        DataType::F32 => Some(f32::from_le_bytes(bytes.get(..4)?.try_into().ok()?) as f64),
        DataType::F64 => Some(f64::from_le_bytes(bytes.get(..8)?.try_into().ok()?)),
        _ => to_int(data_type, bytes).map(|v| v as f64),
    }
}

/// Zeros in the width of `data_type`.
pub fn zero(data_type: DataType) -> Vec<u8> {
    vec![0; data_type.bytes() as usize]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signed_values_round_trip_through_their_width() {
        let i16_type = DataType::Signed(2);
        let bytes = from_int(i16_type, -3000);
        assert_eq!(bytes, vec![0x48, 0xF4]);
        assert_eq!(to_int(i16_type, &bytes), Some(-3000));
    }

    #[test]
    fn odd_widths_sign_extend() {
        let i24 = DataType::Signed(3);
        assert_eq!(to_int(i24, &[0xFF, 0xFF, 0xFF]), Some(-1));
        assert_eq!(
            to_int(DataType::Unsigned(3), &[0xFF, 0xFF, 0xFF]),
            Some(0xFF_FFFF)
        );
    }

    #[test]
    fn floats_are_numbers_but_not_integers() {
        let bytes = 1.5f32.to_le_bytes();
        assert_eq!(to_f64(DataType::F32, &bytes), Some(1.5));
        assert_eq!(to_int(DataType::F32, &bytes), None);
        assert_eq!(to_f64(DataType::F64, &[0; 3]), None, "too short");
    }
}

//! Raw values: the byte and integer conversions are the run-time interpreter's
//! ([`drivebus::interpret::raw`]); the simulator adds the numbers a description writes
//! (defaults, range bounds).

pub use drivebus::interpret::raw::{from_int, to_f64, to_int, zero};
use drivegen::ir::{DataType, Number};

/// The bytes of a described raw number (default, range bound) in the width of `data_type`.
pub fn from_number(data_type: DataType, number: Number) -> Vec<u8> {
    match (data_type, number) {
        (DataType::F32, n) => (n.as_f64() as f32).to_le_bytes().to_vec(),
        (DataType::F64, n) => n.as_f64().to_le_bytes().to_vec(),
        (_, Number::Int(i)) => from_int(data_type, i128::from(i)),
        (_, Number::Float(f)) => from_int(data_type, f as i128),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn described_numbers_take_their_type() {
        let bytes = from_number(DataType::F32, Number::Float(1.5));
        assert_eq!(to_f64(DataType::F32, &bytes), Some(1.5));
        assert_eq!(
            from_number(DataType::Signed(2), Number::Int(-2)),
            [0xFE, 0xFF]
        );
        assert_eq!(from_number(DataType::Unsigned(1), Number::Float(7.0)), [7]);
    }
}

//! The data types a description gives its values, and how wide they are on the wire.
//!
//! One definition for the generator (which picks each parameter's Rust raw type from it), the
//! run-time interpreter and the simulator (which decode bytes by it).

use core::fmt;

/// A description data type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DataType {
    /// `bool`.
    Bool,
    /// Unsigned integer of the given byte width (1..=8).
    Unsigned(u8),
    /// Signed integer of the given byte width (1..=8).
    Signed(u8),
    /// IEEE 754 single.
    F32,
    /// IEEE 754 double.
    F64,
    /// VISIBLE_STRING with a capacity in bytes.
    String(u16),
    /// OCTET_STRING / DOMAIN with a capacity in bytes.
    Octets(u16),
}

const UNSIGNED: [&str; 8] = ["u8", "u16", "u24", "u32", "u40", "u48", "u56", "u64"];
const SIGNED: [&str; 8] = ["i8", "i16", "i24", "i32", "i40", "i48", "i56", "i64"];

impl DataType {
    /// Parses a type name; strings take their capacity from `length`.
    pub fn parse(name: &str, length: u16) -> Option<DataType> {
        let width = |names: &[&str; 8]| names.iter().position(|n| *n == name).map(|i| i as u8 + 1);
        Some(match name {
            "bool" => DataType::Bool,
            "f32" => DataType::F32,
            "f64" => DataType::F64,
            "string" => DataType::String(length),
            "octets" => DataType::Octets(length),
            _ => match width(&UNSIGNED) {
                Some(bytes) => DataType::Unsigned(bytes),
                None => DataType::Signed(width(&SIGNED)?),
            },
        })
    }

    /// The name as written in descriptions (`"u24"`, `"string"`).
    pub const fn name(self) -> &'static str {
        match self {
            DataType::Bool => "bool",
            DataType::Unsigned(b) => UNSIGNED[Self::width_index(b)],
            DataType::Signed(b) => SIGNED[Self::width_index(b)],
            DataType::F32 => "f32",
            DataType::F64 => "f64",
            DataType::String(_) => "string",
            DataType::Octets(_) => "octets",
        }
    }

    /// Index into the width tables; widths outside 1..=8 (never parsed) clamp.
    const fn width_index(bytes: u8) -> usize {
        match bytes {
            0 => 0,
            1..=8 => bytes as usize - 1,
            _ => 7,
        }
    }

    /// Bytes on the wire.
    pub const fn bytes(self) -> u16 {
        match self {
            DataType::Bool => 1,
            DataType::Unsigned(b) | DataType::Signed(b) => b as u16,
            DataType::F32 => 4,
            DataType::F64 => 8,
            DataType::String(n) | DataType::Octets(n) => n,
        }
    }

    /// True for integer types.
    pub const fn is_integer(self) -> bool {
        matches!(self, DataType::Unsigned(_) | DataType::Signed(_))
    }

    /// True for types that can be scaled (integers and floats).
    pub const fn is_numeric(self) -> bool {
        self.is_integer() || matches!(self, DataType::F32 | DataType::F64)
    }

    /// The smallest and largest value of an integer (or bool) type.
    pub const fn integer_bounds(self) -> Option<(i128, i128)> {
        match self {
            DataType::Unsigned(b) => Some((0, (1i128 << (b as u32 * 8)) - 1)),
            DataType::Signed(b) => {
                let half = 1i128 << (b as u32 * 8 - 1);
                Some((-half, half - 1))
            }
            DataType::Bool => Some((0, 1)),
            _ => None,
        }
    }

    /// The Rust type holding a scalar raw value (odd widths round up: `u24` is held in `u32`);
    /// `None` for strings and octets, held in `drivebus::value::Text` of their capacity.
    pub const fn rust_scalar(self) -> Option<&'static str> {
        Some(match self {
            DataType::Bool => "bool",
            DataType::Unsigned(1) => "u8",
            DataType::Unsigned(2) => "u16",
            DataType::Unsigned(3 | 4) => "u32",
            DataType::Unsigned(_) => "u64",
            DataType::Signed(1) => "i8",
            DataType::Signed(2) => "i16",
            DataType::Signed(3 | 4) => "i32",
            DataType::Signed(_) => "i64",
            DataType::F32 => "f32",
            DataType::F64 => "f64",
            DataType::String(_) | DataType::Octets(_) => return None,
        })
    }
}

impl fmt::Display for DataType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Serialized as a map meant to be flattened into its owner: `"type": "u16"`, and for strings and
/// octets also `"length": N` (their capacity in bytes).
#[cfg(feature = "serde")]
impl serde::Serialize for DataType {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let length = match self {
            DataType::String(n) | DataType::Octets(n) => Some(*n),
            _ => None,
        };
        let mut map = serializer.serialize_map(Some(1 + length.is_some() as usize))?;
        map.serialize_entry("type", self.name())?;
        if let Some(n) = length {
            map.serialize_entry("length", &n)?;
        }
        map.end()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_every_width_and_refuses_the_rest() {
        assert_eq!(DataType::parse("u24", 0), Some(DataType::Unsigned(3)));
        assert_eq!(DataType::parse("i56", 0), Some(DataType::Signed(7)));
        assert_eq!(DataType::parse("u12", 0), None);
        assert_eq!(DataType::parse("u128", 0), None);
        assert_eq!(DataType::parse("uint", 0), None);
        assert_eq!(DataType::parse("u08", 0), None);
        assert_eq!(DataType::Unsigned(3).rust_scalar(), Some("u32"));
        assert_eq!(DataType::String(4).rust_scalar(), None);
    }

    #[test]
    fn names_read_back() {
        for name in UNSIGNED
            .iter()
            .chain(&SIGNED)
            .chain(&["bool", "f32", "f64"])
        {
            assert_eq!(DataType::parse(name, 0).map(DataType::name), Some(*name));
        }
    }

    #[test]
    fn bounds_follow_the_wire_width() {
        assert_eq!(DataType::Signed(2).integer_bounds(), Some((-32768, 32767)));
        assert_eq!(DataType::Unsigned(3).integer_bounds(), Some((0, 0xFF_FFFF)));
    }
}

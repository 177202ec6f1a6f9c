//! Description data types and their Rust and wire representations.

use serde::{Serialize, Serializer};

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

impl DataType {
    /// Parses a type name; strings take their capacity from `length`.
    pub fn parse(name: &str, length: u16) -> Option<DataType> {
        let int = |prefix: char| -> Option<u8> {
            let bits: u8 = name.strip_prefix(prefix)?.parse().ok()?;
            (bits % 8 == 0 && (8..=64).contains(&bits)).then_some(bits / 8)
        };
        Some(match name {
            "bool" => DataType::Bool,
            "f32" => DataType::F32,
            "f64" => DataType::F64,
            "string" => DataType::String(length),
            "octets" => DataType::Octets(length),
            _ => {
                if let Some(bytes) = int('u') {
                    DataType::Unsigned(bytes)
                } else {
                    DataType::Signed(int('i')?)
                }
            }
        })
    }

    /// The name as written in descriptions.
    pub fn name(self) -> String {
        match self {
            DataType::Bool => "bool".into(),
            DataType::Unsigned(b) => format!("u{}", b * 8),
            DataType::Signed(b) => format!("i{}", b * 8),
            DataType::F32 => "f32".into(),
            DataType::F64 => "f64".into(),
            DataType::String(_) => "string".into(),
            DataType::Octets(_) => "octets".into(),
        }
    }

    /// Bytes on the wire.
    pub fn bytes(self) -> u16 {
        match self {
            DataType::Bool => 1,
            DataType::Unsigned(b) | DataType::Signed(b) => b as u16,
            DataType::F32 => 4,
            DataType::F64 => 8,
            DataType::String(n) | DataType::Octets(n) => n,
        }
    }

    /// True for integer types.
    pub fn is_integer(self) -> bool {
        matches!(self, DataType::Unsigned(_) | DataType::Signed(_))
    }

    /// True for types that can be scaled (integers and floats).
    pub fn is_numeric(self) -> bool {
        self.is_integer() || matches!(self, DataType::F32 | DataType::F64)
    }

    /// The smallest and largest value of an integer type.
    pub fn integer_bounds(self) -> Option<(i128, i128)> {
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

    /// The Rust type holding the raw value (odd widths round up), as a path string.
    pub fn rust_type(self) -> String {
        match self {
            DataType::Bool => "bool".into(),
            DataType::Unsigned(b) => format!("u{}", rust_width(b)),
            DataType::Signed(b) => format!("i{}", rust_width(b)),
            DataType::F32 => "f32".into(),
            DataType::F64 => "f64".into(),
            DataType::String(n) | DataType::Octets(n) => format!("::drivebus::value::Text<{n}>"),
        }
    }
}

fn rust_width(bytes: u8) -> u32 {
    match bytes {
        1 => 8,
        2 => 16,
        3 | 4 => 32,
        _ => 64,
    }
}

/// Serialized as a map meant to be flattened into its owner: `"type": "u16"`, and for strings and
/// octets also `"length": N` (their capacity in bytes).
impl Serialize for DataType {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let length = match self {
            DataType::String(n) | DataType::Octets(n) => Some(*n),
            _ => None,
        };
        let mut map = serializer.serialize_map(Some(1 + length.is_some() as usize))?;
        map.serialize_entry("type", &self.name())?;
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
        assert_eq!(DataType::Unsigned(3).rust_type(), "u32");
    }

    #[test]
    fn strings_serialize_their_capacity_beside_the_type() {
        #[derive(Serialize)]
        struct Owner {
            #[serde(flatten)]
            data_type: DataType,
        }
        let json = |data_type| serde_json::to_string(&Owner { data_type }).unwrap();
        assert_eq!(
            json(DataType::String(16)),
            r#"{"type":"string","length":16}"#
        );
        assert_eq!(json(DataType::Unsigned(2)), r#"{"type":"u16"}"#);
    }

    #[test]
    fn bounds_follow_the_wire_width() {
        assert_eq!(DataType::Signed(2).integer_bounds(), Some((-32768, 32767)));
        assert_eq!(DataType::Unsigned(3).integer_bounds(), Some((0, 0xFF_FFFF)));
    }
}

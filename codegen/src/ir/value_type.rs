//! The engineering type a parameter's value has in the generated API: what users read and write.

use std::fmt;

use super::{DataType, Parameter};

/// The engineering type of a parameter's value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValueType<'a> {
    /// An open enumeration, by its description name.
    Enum(&'a str),
    /// A bit-flags word, by its description name.
    Flags(&'a str),
    /// A unit newtype of `drivebus::units`, by its type name (`Volts`).
    Unit(&'static str),
    /// A scaled value without a unit newtype, as `f64`.
    Scaled,
    /// The raw value itself.
    Raw(DataType),
}

impl Parameter {
    /// The engineering type of this parameter's value: enumeration, flags, unit newtype, bare
    /// scaled `f64`, or the raw type, in that order of precedence.
    pub fn value_type(&self) -> ValueType<'_> {
        if let Some(e) = &self.enumeration {
            return ValueType::Enum(e);
        }
        if let Some(f) = &self.flags {
            return ValueType::Flags(f);
        }
        match (
            self.unit
                .as_deref()
                .and_then(drivebus_model::units::type_name),
            &self.scale,
        ) {
            (Some(unit), _) => ValueType::Unit(unit),
            (None, Some(_)) => ValueType::Scaled,
            (None, None) => ValueType::Raw(self.data_type),
        }
    }
}

impl fmt::Display for ValueType<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ValueType::Enum(name) => write!(f, "enum `{name}`"),
            ValueType::Flags(name) => write!(f, "flags `{name}`"),
            ValueType::Unit(name) => write!(f, "`{name}`"),
            ValueType::Scaled => f.write_str("`f64`"),
            ValueType::Raw(data_type) => match data_type.rust_scalar() {
                Some(scalar) => write!(f, "`{scalar}`"),
                None => write!(f, "`::drivebus::value::Text<{}>`", data_type.bytes()),
            },
        }
    }
}

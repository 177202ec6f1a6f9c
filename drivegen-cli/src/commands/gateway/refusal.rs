//! Why a set request was refused, in the few kinds an endpoint answers differently: OPC UA has
//! a status code for each (BadOutOfRange, BadTypeMismatch, ...), MQTT says the reason in words.

use drivebus::interpret::InputError;
use drivebus::BusError;

use crate::error::CliError;

/// The kind of a refused write; nothing was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refusal {
    /// Outside the range, the allowed values or the bounds other parameters set.
    OutOfRange,
    /// Not a value of the parameter's type (not a number, not one of its names, a wrong unit).
    WrongType,
    /// The parameter cannot be written here: no such parameter, no write address, another
    /// variant, a drive that is not the described one, or the drive refused it (a Modbus
    /// exception, an SDO abort: locked, read-only in this state).
    NotWritable,
    /// The drive did not answer or the bus failed.
    Communication,
}

/// A refused write: its kind and the reason in words.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refused {
    /// The kind.
    pub kind: Refusal,
    /// The reason, as `drivegen write` would print it.
    pub why: String,
}

impl Refused {
    /// A refusal of `kind` for `why`.
    pub fn new(kind: Refusal, why: impl Into<String>) -> Self {
        Self {
            kind,
            why: why.into(),
        }
    }

    /// The refusal `drivegen write`'s checks gave.
    pub fn of(error: &CliError) -> Self {
        let kind = match error {
            CliError::Value { cause, .. } => match cause {
                InputError::OutOfRange(_)
                | InputError::NotAllowed(_)
                | InputError::NotRepresentable(_) => Refusal::OutOfRange,
                InputError::Unparsable(_)
                | InputError::WrongUnit { .. }
                | InputError::RuntimeScale(_) => Refusal::WrongType,
            },
            CliError::OutsideBound(_) => Refusal::OutOfRange,
            // The drive answered, with a refusal: it was reached.
            CliError::Bus {
                cause: BusError::ModbusException { .. } | BusError::SdoAbort { .. },
                ..
            } => Refusal::NotWritable,
            CliError::Bus { .. } | CliError::Io(_) => Refusal::Communication,
            _ => Refusal::NotWritable,
        };
        Self::new(kind, error.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn input_errors_sort_into_range_and_type() {
        let value = |cause| CliError::Value {
            parameter: "p".into(),
            cause,
            cited: None,
        };
        let range = value(InputError::OutOfRange("above 10".into()));
        assert_eq!(Refused::of(&range).kind, Refusal::OutOfRange);
        assert!(Refused::of(&range).why.contains("above 10"));
        let name = value(InputError::Unparsable("not a number".into()));
        assert_eq!(Refused::of(&name).kind, Refusal::WrongType);
        let bound = CliError::OutsideBound("above max_speed".into());
        assert_eq!(Refused::of(&bound).kind, Refusal::OutOfRange);
        let variant = CliError::Variant("unknown variant".into());
        assert_eq!(Refused::of(&variant).kind, Refusal::NotWritable);
        let bus = |cause| CliError::Bus {
            target: "t".into(),
            parameter: "p".into(),
            cause,
        };
        assert_eq!(
            Refused::of(&bus(BusError::Timeout)).kind,
            Refusal::Communication
        );
    }
}

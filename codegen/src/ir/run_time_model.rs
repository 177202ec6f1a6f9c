//! The IR as the run-time interpreter's device model ([`drivebus::interpret::Model`]): a
//! description loaded at run time is read and written by name through the same scale and checks
//! as generated code.

use drivebus::interpret::{Described, Model, Symbols};

use super::{DataType, Device, Number, Parameter, Range, Scale};

impl Described for Parameter {
    fn name(&self) -> &str {
        &self.name
    }

    fn data_type(&self) -> DataType {
        self.data_type
    }

    fn unit(&self) -> Option<&str> {
        self.unit.as_deref()
    }

    fn fixed_scale(&self) -> Option<drivebus::Scale> {
        match &self.scale {
            None => Some(drivebus::Scale::IDENTITY),
            Some(Scale::Fixed(scale)) => Some(*scale),
            Some(Scale::Runtime { .. }) => None,
        }
    }

    fn range(&self) -> Option<&Range> {
        self.range.as_ref()
    }

    fn allowed(&self) -> &[Number] {
        &self.allowed
    }
}

impl Model for Device {
    type Parameter = Parameter;

    fn parameter(&self, name: &str) -> Option<&Parameter> {
        Device::parameter(self, name)
    }

    fn symbols<'a>(&'a self, parameter: &'a Parameter) -> Symbols<'a> {
        if let Some(e) = parameter
            .enumeration
            .as_deref()
            .and_then(|e| self.enumeration(e))
        {
            return Symbols::Enum {
                name: &e.name,
                values: e
                    .values
                    .iter()
                    .map(|v| (v.name.as_str(), v.value))
                    .collect(),
            };
        }
        if let Some(f) = parameter.flags.as_deref().and_then(|f| self.flags_type(f)) {
            return Symbols::Flags {
                name: &f.name,
                bits: f.bits.iter().map(|b| (b.name.as_str(), b.bit)).collect(),
            };
        }
        Symbols::Plain
    }
}

//! The IR as the run-time interpreter's device model ([`drivebus::interpret::Model`]): a
//! description loaded at run time is read and written by name through the same scale and checks
//! as generated code.

use drivebus::canopen::CanOpen;
use drivebus::interpret::{Access, Addressed, BoundedBy, Described, Model, Symbols};
use drivebus::modbus::Modbus;
use drivebus::rs232::Rs232;

use super::{DataType, Device, Number, ObjectAddress, Parameter, Range, Scale};

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

    fn bounded_by(&self) -> BoundedBy<'_> {
        self.bounds
            .as_ref()
            .map_or_else(BoundedBy::default, |b| BoundedBy {
                min: b.min.as_deref(),
                max: b.max.as_deref(),
                magnitude: b.magnitude.as_deref(),
            })
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

fn allows(access: super::Access, wanted: Access) -> bool {
    match wanted {
        Access::Read => access.read,
        Access::Write => access.write,
    }
}

impl Addressed<Modbus> for Parameter {
    fn address(&self, access: Access) -> Option<drivebus::modbus::ModbusAddress> {
        let described = self.modbus.iter().find(|a| allows(a.access, access))?;
        Some(described.wire)
    }
}

impl Addressed<CanOpen> for Parameter {
    fn address(&self, access: Access) -> Option<drivebus::canopen::ObjectAddress> {
        object_address(self, &self.canopen, access)
    }
}

impl Addressed<Rs232> for Parameter {
    fn address(&self, access: Access) -> Option<drivebus::canopen::ObjectAddress> {
        object_address(self, &self.rs232, access)
    }
}

/// The first of `addresses` (CANopen or RS-232 objects) that allows `access`, with the value's
/// width; 0 (as the object says) for text and octets, which go as long as they are.
fn object_address(
    parameter: &Parameter,
    addresses: &[ObjectAddress],
    access: Access,
) -> Option<drivebus::canopen::ObjectAddress> {
    let object = addresses.iter().find(|a| allows(a.access, access))?;
    let bytes = match parameter.data_type {
        DataType::String(_) | DataType::Octets(_) => 0,
        data_type => data_type.bytes(),
    };
    Some(drivebus::canopen::ObjectAddress {
        index: object.index,
        subindex: object.subindex,
        bytes,
    })
}

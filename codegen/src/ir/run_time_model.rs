//! The IR as the run-time interpreter's device model ([`drivebus::interpret::Model`]): a
//! description loaded at run time is read and written by name through the same scale and checks
//! as generated code.

use drivebus_model::canopen::CanOpen;
use drivebus_model::modbus::Modbus;
use drivebus_model::model::{Access, Addressed, BoundedBy, Described, Model, Symbols, Unreachable};
use drivebus_model::rs232::Rs232;

use super::{DataType, Device, Number, ObjectAddress, Parameter, Range, Scale, StopWrites};

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

    fn fixed_scale(&self) -> Option<drivebus_model::Scale> {
        match &self.scale {
            None => Some(drivebus_model::Scale::IDENTITY),
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

    fn stops(&self) -> drivebus_model::Stops<'_> {
        self.stops
            .as_ref()
            .map_or(drivebus_model::Stops::Never, StopWrites::view)
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

/// The address of `addresses` (each with the variant it is limited to) that serves `access` in
/// `variant`. With the variant unknown (`None`), only an address every variant shares; never the
/// first of several.
fn pick<'a, A: Copy + PartialEq>(
    parameter: &Parameter,
    addresses: impl Iterator<Item = (A, super::Access, Option<&'a str>)>,
    access: Access,
    variant: Option<&str>,
) -> Result<A, Unreachable> {
    let serving: Vec<(A, Option<&str>)> = addresses
        .filter(|(_, a, _)| allows(*a, access))
        .map(|(address, _, only)| (address, only))
        .collect();
    let Some(&(first, _)) = serving.first() else {
        return Err(Unreachable::NoAccess);
    };
    let Some(variant) = variant else {
        let everywhere = parameter.variants.is_empty()
            && serving
                .iter()
                .all(|&(a, only)| a == first && only.is_none());
        return everywhere
            .then_some(first)
            .ok_or(Unreachable::DependsOnVariant);
    };
    let exists = parameter.variants.is_empty() || parameter.variants.iter().any(|v| v == variant);
    serving
        .iter()
        .find(|(_, only)| exists && only.is_none_or(|o| o == variant))
        .map(|&(address, _)| address)
        .ok_or(Unreachable::NotInVariant)
}

impl Addressed<Modbus> for Parameter {
    fn address(
        &self,
        access: Access,
        variant: Option<&str>,
    ) -> Result<drivebus_model::modbus::ModbusAddress, Unreachable> {
        let addresses = self
            .modbus
            .iter()
            .map(|a| (a.wire, a.access, a.variant.as_deref()));
        pick(self, addresses, access, variant)
    }
}

impl Addressed<CanOpen> for Parameter {
    fn address(
        &self,
        access: Access,
        variant: Option<&str>,
    ) -> Result<drivebus_model::canopen::ObjectAddress, Unreachable> {
        object_address(self, &self.canopen, access, variant)
    }
}

impl Addressed<Rs232> for Parameter {
    fn address(
        &self,
        access: Access,
        variant: Option<&str>,
    ) -> Result<drivebus_model::canopen::ObjectAddress, Unreachable> {
        object_address(self, &self.rs232, access, variant)
    }
}

/// The address of `addresses` (CANopen or RS-232 objects) that serves `access` in `variant`,
/// with the value's width; 0 (as the object says) for text and octets, which go as long as they
/// are.
fn object_address(
    parameter: &Parameter,
    addresses: &[ObjectAddress],
    access: Access,
    variant: Option<&str>,
) -> Result<drivebus_model::canopen::ObjectAddress, Unreachable> {
    let bytes = match parameter.data_type {
        DataType::String(_) | DataType::Octets(_) => 0,
        data_type => data_type.bytes(),
    };
    let addresses = addresses.iter().map(|a| {
        let address = drivebus_model::canopen::ObjectAddress {
            index: a.index,
            subindex: a.subindex,
            bytes,
        };
        (address, a.access, a.variant.as_deref())
    });
    pick(parameter, addresses, access, variant)
}

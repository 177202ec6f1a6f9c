//! The parameter configuration is chosen by the drive: register #50 reads 400 (PC400) or 507
//! (PC507) (section 3.3, line 314; Table 2, line 276). [`LenzeSmd::detect_configuration`] reads
//! it and selects the matching variant; any other number leaves reads working and makes the
//! crate's write helpers refuse ([`SmdError::UnknownConfiguration`]) before anything is sent.

use drivebus::modbus::{ModbusLink, RegisterBus, UnitId};
use drivebus::{Error, Link};

use crate::error::SmdError;
use crate::types::ParameterConfiguration;
use crate::{LenzeSmd, Variant};

/// What register #50 says about the drive's register map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Configuration {
    /// A configuration the description covers.
    Known(Variant),
    /// Any other number: reads still work, writes must not be attempted.
    Unknown(u16),
}

impl Configuration {
    /// The configuration a value of register #50 stands for.
    pub fn from_number(number: ParameterConfiguration) -> Self {
        if number == ParameterConfiguration::PC400 {
            Self::Known(Variant::Pc400)
        } else if number == ParameterConfiguration::PC507 {
            Self::Known(Variant::Pc507)
        } else {
            Self::Unknown(number.raw())
        }
    }

    /// The variant, or [`SmdError::UnknownConfiguration`] naming the number found.
    pub fn variant(self) -> Result<Variant, SmdError> {
        match self {
            Self::Known(variant) => Ok(variant),
            Self::Unknown(value) => Err(SmdError::UnknownConfiguration { value }),
        }
    }
}

impl<L: Link<Protocol = drivebus::modbus::Modbus>> LenzeSmd<L> {
    /// Reads register #50 and selects the variant it names. With an unknown number the
    /// selected variant stays as it was (the default, PC400, unless [`LenzeSmd::set_variant`]
    /// chose another: the override for users who know the drive).
    pub fn detect_configuration(&mut self) -> Result<Configuration, Error> {
        let configuration = Configuration::from_number(self.parameter_configuration().read()?);
        if let Configuration::Known(variant) = configuration {
            self.set_variant(variant);
        }
        Ok(configuration)
    }
}

impl<B: RegisterBus> LenzeSmd<ModbusLink<B>> {
    /// Opens the drive at `unit` and selects its configuration from register #50. The handle is
    /// returned with what #50 said, also when the number is unknown (reads work then).
    pub fn open(bus: B, unit: UnitId) -> Result<(Self, Configuration), Error> {
        let mut drive = Self::modbus(bus, unit);
        let configuration = drive.detect_configuration()?;
        Ok((drive, configuration))
    }
}

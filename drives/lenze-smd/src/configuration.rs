//! The parameter configuration is chosen by the drive: register #50 reads 400 (PC400) or 507
//! (PC507) (section 3.3, line 314; Table 2, line 276). The description says so as data
//! (`[[variant]] selected_by`), from which the generated [`LenzeSmd::detect_variant`] reads #50 and
//! selects the variant. Any other number leaves reads working and makes the crate's write
//! helpers refuse ([`SmdError::UnknownConfiguration`]) before anything is sent.

use drivebus::modbus::{ModbusLink, RegisterBus, UnitId};
use drivebus::Error;

use crate::error::SmdError;
use crate::{LenzeSmd, Variant, VariantSelection};

impl VariantSelection {
    /// The variant, or [`SmdError::UnknownConfiguration`] naming the number found: writing to
    /// a drive in an unknown configuration "MUST NOT BE ATTEMPTED" (line 314).
    pub fn writable(self) -> Result<Variant, SmdError> {
        match self {
            Self::Known(variant) => Ok(variant),
            Self::Unknown(value) => Err(SmdError::UnknownConfiguration { value }),
        }
    }
}

impl<B: RegisterBus> LenzeSmd<ModbusLink<B>> {
    /// Opens the drive at `unit` and selects its configuration from register #50. The handle is
    /// returned with what #50 said, also when the number is unknown (reads work then).
    pub fn open(bus: B, unit: UnitId) -> Result<(Self, VariantSelection), Error> {
        let mut drive = Self::modbus(bus, unit);
        let selection = drive.detect_variant()?;
        Ok((drive, selection))
    }
}

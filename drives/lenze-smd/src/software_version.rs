//! C99, the software version: a 4-word read at one register (#89 in PC400, #95 in PC507; section
//! 2.3 D line 229, section 6.1 lines 833-836), text such as "SMD 1.51" (line 926), each word high
//! byte first like every smd register (Note 4a, line 639).

use drivebus::modbus::{Modbus, ModbusLink, RegisterBus};
use drivebus::value::Text;
use drivebus::{Error, Parameter, Readable, ValueError};

use crate::params::SoftwareVersion;
use crate::LenzeSmd;

/// Words of C99.
const WORDS: usize = 4;

impl<B: RegisterBus> LenzeSmd<ModbusLink<B>> {
    /// Reads C99 in one 4-word request at its register in the selected configuration.
    pub fn read_software_version(&mut self) -> Result<Text<8>, Error> {
        let variant = self.device().variant();
        let address = <SoftwareVersion as Readable<Modbus>>::read_address(variant).ok_or(
            Error::NotInVariant {
                parameter: SoftwareVersion::NAME,
            },
        )?;
        let mut words = [0u16; WORDS];
        let link = self.device().link_mut();
        let unit = link.unit();
        link.bus_mut()
            .read_registers(unit, address.table, address.address, &mut words)
            .map_err(|cause| Error::Bus {
                parameter: SoftwareVersion::NAME,
                cause,
            })?;
        version_text(words)
    }
}

/// The text of C99's words: high byte first, trailing NULs dropped.
pub fn version_text(words: [u16; WORDS]) -> Result<Text<8>, Error> {
    let mut bytes = [0u8; 2 * WORDS];
    for (pair, word) in bytes.chunks_exact_mut(2).zip(words) {
        pair.copy_from_slice(&word.to_be_bytes());
    }
    let end = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
    Text::from_bytes(&bytes[..end]).ok_or(Error::Value(ValueError::BadText))
}

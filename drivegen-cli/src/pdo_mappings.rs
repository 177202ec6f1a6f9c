//! PDO mappings learned from a capture: the SDO writes to the mapping objects (1600h.., 1A00h..)
//! say which objects later PDO payloads carry.

use drivebus::canopen::pdo::{MappedObject, PdoKind};

use crate::frames::{Sample, Samples};
use crate::objects::{AddressMap, Objects};

/// First RPDO and TPDO mapping objects.
const RPDO_MAPPING: u16 = 0x1600;
const TPDO_MAPPING: u16 = 0x1A00;
/// Mapping objects per direction.
const MAPPINGS: u16 = 0x200;

/// The mappings seen so far, per node, direction and PDO number.
#[derive(Debug, Default)]
pub struct PdoMappings {
    maps: AddressMap<(u8, bool, u16), Vec<MappedObject>>,
}

impl PdoMappings {
    /// Learns from an SDO download of `data` to `index:subindex` of `node`; other objects are
    /// ignored.
    pub fn learn(&mut self, node: u8, index: u16, subindex: u8, data: &[u8]) {
        let (transmit, number) = match index {
            i if (TPDO_MAPPING..TPDO_MAPPING + MAPPINGS).contains(&i) => {
                (true, i - TPDO_MAPPING + 1)
            }
            i if (RPDO_MAPPING..RPDO_MAPPING + MAPPINGS).contains(&i) => {
                (false, i - RPDO_MAPPING + 1)
            }
            _ => return,
        };
        let mut bytes = [0u8; 4];
        let n = data.len().min(4);
        bytes[..n].copy_from_slice(&data[..n]);
        let value = u32::from_le_bytes(bytes);
        let entries = self.maps.entry((node, transmit, number)).or_default();
        if subindex == 0 {
            entries.truncate(value as usize);
            return;
        }
        let slot = usize::from(subindex) - 1;
        if entries.len() <= slot {
            entries.resize(slot + 1, MappedObject::new(0, 0, 0));
        }
        entries[slot] = MappedObject::from_entry(value);
    }

    /// The parameter values of a PDO payload into `values` (empty before), if its mapping is
    /// known and the payload holds it: the mapping seen in the capture, else the one the
    /// description declares for the PDO. `false` (and `values` left empty) if not. Filled in
    /// place: a frame's values are not moved from one buffer to the next.
    pub fn decode<'a>(
        &self,
        objects: &'a Objects<'a>,
        pdo: (u8, PdoKind, u8),
        payload: &[u8],
        values: &mut Samples<'a>,
    ) -> bool {
        let (node, kind, number) = pdo;
        let transmit = kind == PdoKind::Transmit;
        let entries = match self.maps.get(&(node, transmit, u16::from(number))) {
            Some(learned) => learned.as_slice(),
            None => match objects.declared_mapping(transmit, number) {
                Some(declared) => declared,
                None => return false,
            },
        };
        let mut bit = 0usize;
        for entry in entries {
            let at = bit / 8..bit / 8 + usize::from(entry.bits) / 8;
            // Bit-packed mappings are left raw.
            let bytes = payload
                .get(at)
                .filter(|_| bit % 8 == 0 && entry.bits % 8 == 0);
            let Some(bytes) = bytes else {
                values.clear();
                return false;
            };
            bit += usize::from(entry.bits);
            values.push(Sample::of(objects, entry.index, entry.subindex, bytes));
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_learned_mapping_names_the_payload() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../descriptions/lafert-smartris"
        );
        let device = drivegen::check(std::path::Path::new(path)).device.unwrap();
        let device = Objects::new(&device);
        let mut maps = PdoMappings::default();
        maps.learn(1, 0x1A00, 0, &[0]);
        maps.learn(1, 0x1A00, 1, &0x6041_0010u32.to_le_bytes());
        maps.learn(1, 0x1A00, 2, &0x606C_0020u32.to_le_bytes());
        maps.learn(1, 0x1A00, 0, &[2]);
        let payload = [0x37, 0x00, 0xE8, 0x03, 0x00, 0x00];
        let decode = |kind, number| {
            let mut samples = Samples::new();
            let known = maps.decode(&device, (1, kind, number), &payload, &mut samples);
            known.then(|| -> Vec<(String, Option<f64>)> {
                samples
                    .iter()
                    .map(|s| (s.parameter().to_string(), s.value()))
                    .collect()
            })
        };
        assert_eq!(
            decode(PdoKind::Transmit, 1).unwrap(),
            [
                ("statusword".to_owned(), Some(55.0)),
                ("velocity_actual_value".to_owned(), Some(1000.0))
            ]
        );
        assert!(
            decode(PdoKind::Receive, 2).is_none(),
            "neither learned nor declared"
        );
        // TPDO 2 was not seen being mapped: the description's mapping decodes it.
        assert_eq!(
            decode(PdoKind::Transmit, 2).unwrap()[1],
            ("position_actual_value".to_owned(), Some(1000.0))
        );
    }
}

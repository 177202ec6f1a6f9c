//! A TPDO's configuration as the drive holds it (communication object 1800h + n − 1, mapping
//! object 1A00h + n − 1): read before `watch --pdo` changes it, written back when it ends.

use drivebus::canopen::pdo::{MappedObject, PdoConfig, PdoKind, COB_ID_INVALID};
use drivebus::canopen::{NodeId, SdoBus};
use drivebus::BusError;

/// A TPDO's configuration.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TpdoConfig {
    /// TPDO number, 1..=512.
    pub number: u16,
    /// Communication sub-index 1, the "not valid" bit 31 included.
    pub cob_id: u32,
    /// Sub-index 2; `None` where the drive has no such sub-index.
    pub transmission_type: Option<u8>,
    /// Sub-index 3, in 100 µs; `None` where the drive has no such sub-index.
    pub inhibit_time: Option<u16>,
    /// Sub-index 5, in ms; `None` where the drive has no such sub-index.
    pub event_timer: Option<u16>,
    /// The mapping entries.
    pub entries: Vec<MappedObject>,
    /// The raw mapping sub-indices after the entry count, as far as the drive answers (up to
    /// 8 in all): not in use, but a watch that maps more entries overwrites them, and they are
    /// written back as they were.
    pub beyond: Vec<u32>,
}

impl TpdoConfig {
    /// Reads TPDO `number` of `node`. Sub-indices 2, 3 and 5 are optional (a description may
    /// leave them out): one the drive refuses is left `None` (and never written).
    pub fn read<B: SdoBus + ?Sized>(
        bus: &mut B,
        node: NodeId,
        number: u16,
    ) -> Result<Self, BusError> {
        let (communication, mapping) = indices(number);
        let cob_id = upload_u32(bus, node, communication, 1)?;
        let transmission_type = upload_u32(bus, node, communication, 2)
            .ok()
            .map(|t| t as u8);
        let inhibit_time = upload_u32(bus, node, communication, 3)
            .ok()
            .map(|t| t as u16);
        let event_timer = upload_u32(bus, node, communication, 5)
            .ok()
            .map(|t| t as u16);
        let count = upload_u32(bus, node, mapping, 0)?;
        let count = count.min(64) as u8;
        let entries = (1..=count)
            .map(|sub| upload_u32(bus, node, mapping, sub).map(MappedObject::from_entry))
            .collect::<Result<_, _>>()?;
        let beyond = (count + 1..=8)
            .map_while(|sub| upload_u32(bus, node, mapping, sub).ok())
            .collect();
        Ok(Self {
            number,
            cob_id,
            transmission_type,
            inhibit_time,
            event_timer,
            entries,
            beyond,
        })
    }

    /// The CAN identifier it goes out on (COB-ID bits 0-10).
    pub fn can_id(&self) -> u16 {
        (self.cob_id & 0x7FF) as u16
    }

    /// Whether the PDO is valid (COB-ID bit 31 clear).
    pub fn is_valid(&self) -> bool {
        self.cob_id & COB_ID_INVALID == 0
    }

    /// Writes this configuration to `node` in the order CiA 301 requires (the PDO disabled
    /// while it changes; a configuration held not valid is left not valid), then the unused
    /// sub-indices after the entry count as they were (a drive that refuses one is left so:
    /// they are not in use).
    pub fn write<B: SdoBus + ?Sized>(&self, bus: &mut B, node: NodeId) -> Result<(), BusError> {
        let config = PdoConfig {
            kind: PdoKind::Transmit,
            number: self.number,
            cob_id: self.cob_id & !COB_ID_INVALID,
            transmission_type: self.transmission_type,
            inhibit_time: self.inhibit_time,
            event_timer: self.event_timer,
            entries: &self.entries,
        };
        let mut writes: Vec<_> = config.plan()?.collect();
        if !self.is_valid() {
            // The plan's last write enables the PDO; its first already wrote the COB-ID as held.
            writes.pop();
        }
        for write in writes {
            bus.download(node, write.index, write.subindex, write.data())?;
        }
        let (_, mapping) = indices(self.number);
        for (sub, raw) in (self.entries.len() as u8 + 1..).zip(&self.beyond) {
            let _ = bus.download(node, mapping, sub, &raw.to_le_bytes());
        }
        Ok(())
    }

    /// The byte offset of each of `objects` in this TPDO's payload, if it maps them all, each
    /// whole bytes at a whole byte, with its width.
    pub fn offsets(&self, objects: &[MappedObject]) -> Option<Vec<usize>> {
        let mut at = Vec::with_capacity(self.entries.len());
        let mut bit = 0usize;
        for entry in &self.entries {
            at.push((bit % 8 == 0 && entry.bits % 8 == 0).then_some(bit / 8));
            bit += usize::from(entry.bits);
        }
        objects
            .iter()
            .map(|wanted| {
                let i = self.entries.iter().position(|e| e == wanted)?;
                at[i]
            })
            .collect()
    }
}

/// The communication and mapping object indices of TPDO `number`.
fn indices(number: u16) -> (u16, u16) {
    (0x1800 + number - 1, 0x1A00 + number - 1)
}

/// An unsigned value of up to 4 bytes, little-endian.
fn upload_u32<B: SdoBus + ?Sized>(
    bus: &mut B,
    node: NodeId,
    index: u16,
    subindex: u8,
) -> Result<u32, BusError> {
    let mut bytes = [0u8; 4];
    let n = bus.upload(node, index, subindex, &mut bytes)?;
    if n == 0 || n > 4 {
        return Err(BusError::Frame("PDO object of an unexpected size"));
    }
    Ok(u32::from_le_bytes(bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config(entries: Vec<MappedObject>) -> TpdoConfig {
        TpdoConfig {
            number: 1,
            cob_id: 0x181,
            transmission_type: Some(1),
            inhibit_time: None,
            event_timer: None,
            entries,
            beyond: Vec::new(),
        }
    }

    #[test]
    fn offsets_are_found_only_at_whole_bytes() {
        let statusword = MappedObject::new(0x6041, 0, 16);
        let velocity = MappedObject::new(0x606C, 0, 32);
        let flag = MappedObject::new(0x2000, 1, 1);
        let tpdo = config(vec![statusword, velocity]);
        assert_eq!(tpdo.offsets(&[velocity, statusword]), Some(vec![2, 0]));
        assert_eq!(tpdo.offsets(&[MappedObject::new(0x6064, 0, 32)]), None);
        let packed = config(vec![flag, velocity]);
        assert_eq!(packed.offsets(&[velocity]), None, "at bit 1");
    }
}

//! A PDO configured at boot: what the node is told through [`PdoConfig`], and the state its
//! objects hold afterwards (what a second boot compares before writing anything).

use std::vec::Vec;

use super::BootWrite;
use crate::canopen::address::NodeId;
use crate::canopen::pdo::{MappedObject, PdoConfig, PdoKind};
use crate::error::BusError;

/// Bit 30 of a PDO COB-ID: no RTR allowed. Devices may report it set whatever was written, so
/// a comparison leaves it out.
const COB_ID_NO_RTR: u32 = 0x4000_0000;

/// One PDO to configure at boot (owned; [`Self::config`] lends it to [`PdoConfig`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PdoSetup {
    /// RPDO or TPDO.
    pub kind: PdoKind,
    /// PDO number, 1..=512.
    pub number: u16,
    /// COB-ID without the "invalid" bit 31.
    pub cob_id: u32,
    /// Transmission type (sub 2), if it is to be set.
    pub transmission_type: Option<u8>,
    /// Inhibit time in 100 µs (sub 3), if it is to be set.
    pub inhibit_time: Option<u16>,
    /// Event timer in ms (sub 5), if it is to be set.
    pub event_timer: Option<u16>,
    /// The mapped objects, in payload order.
    pub entries: Vec<MappedObject>,
}

impl PdoSetup {
    /// The COB-ID PDO `number` of `node` has in the predefined connection set (CiA 301
    /// §7.3.5): PDOs 1-4; `None` for other numbers.
    pub fn default_cob_id(kind: PdoKind, number: u16, node: NodeId) -> Option<u32> {
        let transmit = matches!(kind, PdoKind::Transmit);
        drivebus_model::canopen::predefined_pdo_cob_id(transmit, number, node.get())
    }

    /// The configuration the existing PDO code applies (disable, map, enable).
    pub fn config(&self) -> PdoConfig<'_> {
        PdoConfig {
            kind: self.kind,
            number: self.number,
            cob_id: self.cob_id,
            transmission_type: self.transmission_type,
            inhibit_time: self.inhibit_time,
            event_timer: self.event_timer,
            entries: &self.entries,
        }
    }

    /// The writes of [`PdoConfig::plan`], in order.
    pub(super) fn writes(&self) -> Result<Vec<BootWrite>, BusError> {
        Ok(self.config().plan()?.map(|w| boot_write(&w)).collect())
    }

    /// What the objects hold once configured: for every object the plan writes, its last
    /// value (the COB-ID valid, the entry count `n`), in the plan's order.
    pub(super) fn target(&self) -> Result<Vec<BootWrite>, BusError> {
        let mut last: Vec<BootWrite> = Vec::new();
        for write in self.writes()? {
            match last
                .iter_mut()
                .find(|w| (w.index, w.subindex) == (write.index, write.subindex))
            {
                Some(earlier) => *earlier = write,
                None => last.push(write),
            }
        }
        Ok(last)
    }

    /// The bits of object `index:subindex` a comparison looks at: all of them but bit 30 of
    /// the COB-ID.
    pub(super) fn compared_bits(&self, index: u16, subindex: u8) -> u32 {
        let cob_id = (self.config().communication_index(), 1);
        if (index, subindex) == cob_id {
            !COB_ID_NO_RTR
        } else {
            u32::MAX
        }
    }
}

fn boot_write(write: &crate::canopen::pdo::SdoWrite) -> BootWrite {
    BootWrite {
        index: write.index,
        subindex: write.subindex,
        data: write.data().to_vec(),
    }
}

#[cfg(test)]
mod tests {
    use std::vec;

    use super::*;

    fn setup() -> PdoSetup {
        PdoSetup {
            kind: PdoKind::Transmit,
            number: 1,
            cob_id: 0x181,
            transmission_type: Some(254),
            inhibit_time: None,
            event_timer: Some(50),
            entries: vec![MappedObject::new(0x6041, 0, 16)],
        }
    }

    #[test]
    fn the_target_is_the_last_value_of_every_written_object() {
        let target = setup().target().unwrap();
        let addresses: Vec<_> = target
            .iter()
            .map(|w| (w.index, w.subindex, w.data.clone()))
            .collect();
        assert_eq!(
            addresses,
            [
                (0x1800, 1, 0x181u32.to_le_bytes().to_vec()),
                (0x1800, 2, vec![254]),
                (0x1800, 5, vec![50, 0]),
                (0x1A00, 0, vec![1]),
                (0x1A00, 1, 0x6041_0010u32.to_le_bytes().to_vec()),
            ]
        );
        assert_eq!(setup().writes().unwrap().len(), 7);
    }

    #[test]
    fn the_predefined_connection_set_gives_pdos_1_to_4() {
        let node = NodeId(5);
        assert_eq!(
            PdoSetup::default_cob_id(PdoKind::Transmit, 1, node),
            Some(0x185)
        );
        assert_eq!(
            PdoSetup::default_cob_id(PdoKind::Receive, 4, node),
            Some(0x505)
        );
        assert_eq!(PdoSetup::default_cob_id(PdoKind::Transmit, 5, node), None);
        assert_eq!(setup().compared_bits(0x1800, 1), !0x4000_0000);
        assert_eq!(setup().compared_bits(0x1A00, 1), u32::MAX);
    }
}

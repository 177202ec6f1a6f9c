//! A PDO configured at boot: the writes [`PdoConfig`] plans for a [`PdoSetup`], and the state
//! its objects hold afterwards (what a second boot compares before writing anything).

use std::vec::Vec;

use super::BootWrite;
use crate::canopen::pdo::{PdoConfig, PdoSetup, SdoWrite};
use crate::error::BusError;

/// Bit 30 of a PDO COB-ID: no RTR allowed. Devices may report it set whatever was written, so
/// a comparison leaves it out.
const COB_ID_NO_RTR: u32 = 0x4000_0000;

/// The writes of [`PdoConfig::plan`], in order.
pub(super) fn writes(setup: &PdoSetup) -> Result<Vec<BootWrite>, BusError> {
    Ok(PdoConfig::from(setup).plan()?.map(boot_write).collect())
}

/// What the objects hold once configured: for every object the plan writes, its last value
/// (the COB-ID valid, the entry count `n`), in the plan's order.
pub(super) fn target(setup: &PdoSetup) -> Result<Vec<BootWrite>, BusError> {
    let mut last: Vec<BootWrite> = Vec::new();
    for write in writes(setup)? {
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

/// The bits of object `index:subindex` a comparison looks at: all of them but bit 30 of the
/// COB-ID.
pub(super) fn compared_bits(setup: &PdoSetup, index: u16, subindex: u8) -> u32 {
    let cob_id = (PdoConfig::from(setup).communication_index(), 1);
    if (index, subindex) == cob_id {
        !COB_ID_NO_RTR
    } else {
        u32::MAX
    }
}

fn boot_write(write: SdoWrite) -> BootWrite {
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
    use crate::canopen::pdo::{MappedObject, PdoKind};

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
        let target = target(&setup()).unwrap();
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
        assert_eq!(writes(&setup()).unwrap().len(), 7);
    }

    #[test]
    fn the_cob_id_is_compared_without_bit_30() {
        assert_eq!(
            PdoSetup::default_cob_id(PdoKind::Transmit, 1, 5),
            Some(0x185)
        );
        assert_eq!(compared_bits(&setup(), 0x1800, 1), !0x4000_0000);
        assert_eq!(compared_bits(&setup(), 0x1A00, 1), u32::MAX);
    }
}

//! The LSS slave (CiA 305) of a simulated node, for drives whose description says they are one
//! (`[canopen] lss`): its LSS address is the drive's identity object 1018h sub 1-4 as the
//! simulator holds it, so `--set serial_number=...` gives each simulated drive its own.

use drivebus::canopen::lss::{BitTiming, LssAddress, LssSlave};

use crate::behaviour::object;
use crate::store::Store;

/// The drive's LSS slave at node id `node` (FFh: none) and bit rate `bits`, or `None` if its
/// description does not make it one.
pub fn slave(store: &Store, node: u8, bits: u32) -> Option<LssSlave> {
    store.device().canopen.as_ref()?.lss.as_ref()?;
    let word = |sub| {
        object(store, 0x1018, sub)
            .and_then(|id| store.int(id))
            .and_then(|v| u32::try_from(v).ok())
            .unwrap_or(0)
    };
    let address = LssAddress::from_words([word(1), word(2), word(3), word(4)]);
    let timing = BitTiming::from_bits_per_second(bits).unwrap_or(BitTiming::K1000);
    Some(LssSlave::new(address, node, timing))
}

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
    let slave = LssSlave::new(address, node, timing);
    Some(match described_timings(store) {
        Some(timings) => slave.with_bit_timings(&timings),
        None => slave,
    })
}

/// The bit rates the drive documents: the values of the CANopen bit rate parameter's
/// enumeration (named `kbit_1000`, ... as `drivegen sim` reads the default bit rate), if it
/// has one. A bit rate the drive does not list is refused with LSS error code 1.
fn described_timings(store: &Store) -> Option<Vec<BitTiming>> {
    let device = store.device();
    device
        .parameters
        .iter()
        .filter(|p| !p.canopen.is_empty())
        .filter_map(|p| {
            device
                .enums
                .iter()
                .find(|e| Some(&e.name) == p.enumeration.as_ref())
        })
        .find_map(|e| {
            e.values
                .iter()
                .map(|v| {
                    let kbit: u32 = v.name.strip_prefix("kbit_")?.parse().ok()?;
                    BitTiming::from_bits_per_second(kbit * 1000)
                })
                .collect::<Option<Vec<_>>>()
        })
}

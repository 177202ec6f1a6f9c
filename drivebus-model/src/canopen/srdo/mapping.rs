//! SRDO mappings: the mapping object (1381h..) lists the entries interleaved, normal data at the
//! odd sub-indices, its inverted copy at the even ones (SWD manual lines 1745-1746, 1767-1782).
//!
//! The normal entries are packed into the normal frame exactly as a PDO is, so the normal data
//! decodes with a `drivebus::canopen::pdo::PdoLayout` of the normal entries.

use super::error::SrdoError;
use crate::canopen::{mapping_bits, MappedObject};

/// Checks a mapping as the mapping object holds it: an even number of entries, each 1..=64 bits,
/// every inverted entry as wide as the normal entry before it, and the normal data within one
/// 8-byte frame (so at most 128 entries and 128 bits for the pair). Usable in constants.
pub const fn check_mapping(entries: &[MappedObject]) -> Result<(), SrdoError> {
    if entries.is_empty() || entries.len() % 2 != 0 {
        return Err(SrdoError::BadConfiguration(
            "an SRDO maps pairs of entries: normal data, then its inverted copy",
        ));
    }
    let mut i = 0;
    while i < entries.len() {
        let bits = entries[i].bits;
        if bits == 0 || bits > 64 {
            return Err(SrdoError::BadConfiguration(
                "an SRDO entry must be 1..=64 bits",
            ));
        }
        if i % 2 == 1 && bits != entries[i - 1].bits {
            return Err(SrdoError::BadConfiguration(
                "an inverted SRDO entry must be as wide as its normal entry",
            ));
        }
        i += 1;
    }
    if data_bits(entries) > 64 {
        return Err(SrdoError::BadConfiguration(
            "the normal data of an SRDO must fit one 8-byte frame",
        ));
    }
    Ok(())
}

/// Whether [`check_mapping`] accepts `entries` (for `assert!` in constants).
pub const fn mapping_is_valid(entries: &[MappedObject]) -> bool {
    check_mapping(entries).is_ok()
}

/// Bits of the normal data: the sum of the entries at odd sub-indices.
pub const fn data_bits(entries: &[MappedObject]) -> u32 {
    let mut total = 0;
    let mut i = 0;
    while i < entries.len() {
        total += entries[i].bits as u32;
        i += 2;
    }
    total
}

/// Bytes of each frame of the pair.
pub const fn frame_bytes(entries: &[MappedObject]) -> u8 {
    data_bits(entries).div_ceil(8) as u8
}

/// The normal-data entries (sub-indices 1, 3, 5, ...) of an interleaved mapping of `2 × N`
/// entries. Panics (a compile error in a constant) if the mapping has another length.
pub const fn normal_entries<const N: usize>(entries: &[MappedObject]) -> [MappedObject; N] {
    assert!(entries.len() == 2 * N, "SRDO mapping length is not 2 × N");
    let mut out = [MappedObject::new(0, 0, 0); N];
    let mut i = 0;
    while i < N {
        out[i] = entries[2 * i];
        i += 1;
    }
    out
}

/// Bits of the whole pair (normal and inverted data), as the mapping object counts them.
pub const fn pair_bits(entries: &[MappedObject]) -> u32 {
    mapping_bits(entries)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// SRDO1's default mapping, SWD manual lines 1745-1746.
    const SRDO1: [MappedObject; 2] = [
        MappedObject::from_entry(0x6620_0108),
        MappedObject::from_entry(0x6622_0108),
    ];

    /// SRDO10's default mapping, SWD manual lines 1817-1820: two i32 and their inverted copies,
    /// 128 bits for the pair.
    const SRDO10: [MappedObject; 4] = [
        MappedObject::from_entry(0x6611_0020),
        MappedObject::from_entry(0x661A_0020),
        MappedObject::from_entry(0x6613_0020),
        MappedObject::from_entry(0x661C_0020),
    ];

    #[test]
    fn default_mappings_are_valid() {
        assert_eq!(check_mapping(&SRDO1), Ok(()));
        assert_eq!(check_mapping(&SRDO10), Ok(()));
        assert_eq!(frame_bytes(&SRDO1), 1);
        assert_eq!(frame_bytes(&SRDO10), 8);
        assert_eq!(pair_bits(&SRDO10), 128);
    }

    #[test]
    fn normal_entries_take_the_odd_sub_indices() {
        let normal: [MappedObject; 2] = normal_entries(&SRDO10);
        assert_eq!(normal[0].index, 0x6611);
        assert_eq!(normal[1].index, 0x6613);
    }

    #[test]
    fn bad_mappings_are_refused() {
        assert!(check_mapping(&[]).is_err());
        assert!(check_mapping(&SRDO1[..1]).is_err());
        let unequal = [
            MappedObject::new(0x6620, 1, 8),
            MappedObject::new(0x6622, 1, 16),
        ];
        assert!(check_mapping(&unequal).is_err());
        let zero = [
            MappedObject::new(0x6620, 1, 0),
            MappedObject::new(0x6622, 1, 0),
        ];
        assert!(check_mapping(&zero).is_err());
        let too_wide = [
            MappedObject::new(0x6611, 0, 64),
            MappedObject::new(0x661A, 0, 64),
            MappedObject::new(0x6620, 1, 8),
            MappedObject::new(0x6622, 1, 8),
        ];
        assert!(check_mapping(&too_wide).is_err());
    }
}

//! PDO mapping entries: which object a mapping takes, how many bits of the frame, and whether a
//! mapping fits one classic CAN frame. SRDO mappings are built of the same entries.

/// One mapped object: which entry, and how many bits of the payload it takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MappedObject {
    /// Object index.
    pub index: u16,
    /// Subindex.
    pub subindex: u8,
    /// Length in bits (1..=64).
    pub bits: u8,
}

impl MappedObject {
    /// An entry of `bits` bits.
    pub const fn new(index: u16, subindex: u8, bits: u8) -> Self {
        Self {
            index,
            subindex,
            bits,
        }
    }

    /// The 32-bit value written to a mapping object (0x1600.., 0x1A00..).
    pub const fn entry(self) -> u32 {
        ((self.index as u32) << 16) | ((self.subindex as u32) << 8) | self.bits as u32
    }

    /// The entry a mapping object holds.
    pub const fn from_entry(entry: u32) -> Self {
        Self::new((entry >> 16) as u16, (entry >> 8) as u8, entry as u8)
    }
}

/// Total bits of a mapping.
pub const fn mapping_bits(entries: &[MappedObject]) -> u32 {
    let mut total = 0;
    let mut i = 0;
    while i < entries.len() {
        total += entries[i].bits as u32;
        i += 1;
    }
    total
}

/// Whether a mapping fits one classic CAN frame: every entry 1..=64 bits, 64 bits in total.
/// Usable in constants, so generated code rejects an oversized mapping at compile time.
pub const fn mapping_fits(entries: &[MappedObject]) -> bool {
    let mut i = 0;
    while i < entries.len() {
        if entries[i].bits == 0 || entries[i].bits > 64 {
            return false;
        }
        i += 1;
    }
    mapping_bits(entries) <= 64
}

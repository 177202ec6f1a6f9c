//! The CiA 305 bit timing table (table selector 0): the index a "configure bit timing" command
//! carries for each standard bit rate.

/// A bit rate of the CiA 305 standard table (table selector 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BitTiming {
    /// 1 Mbit/s (index 0).
    K1000,
    /// 800 kbit/s (index 1).
    K800,
    /// 500 kbit/s (index 2).
    K500,
    /// 250 kbit/s (index 3).
    K250,
    /// 125 kbit/s (index 4).
    K125,
    /// 100 kbit/s (index 5; python canopen 2.4.1 and CANopenNode use this index for it).
    K100,
    /// 50 kbit/s (index 6).
    K50,
    /// 20 kbit/s (index 7).
    K20,
    /// 10 kbit/s (index 8).
    K10,
    /// Automatic bit rate detection (index 9).
    Auto,
}

impl BitTiming {
    /// Every entry, by index.
    pub const ALL: [Self; 10] = [
        Self::K1000,
        Self::K800,
        Self::K500,
        Self::K250,
        Self::K125,
        Self::K100,
        Self::K50,
        Self::K20,
        Self::K10,
        Self::Auto,
    ];

    /// The table index.
    pub const fn index(self) -> u8 {
        self as u8
    }

    /// The entry at `index`, if the table has one.
    pub fn from_index(index: u8) -> Option<Self> {
        Self::ALL.get(usize::from(index)).copied()
    }

    /// The bit rate in bit/s (`None` for automatic detection).
    pub const fn bits_per_second(self) -> Option<u32> {
        Some(match self {
            Self::K1000 => 1_000_000,
            Self::K800 => 800_000,
            Self::K500 => 500_000,
            Self::K250 => 250_000,
            Self::K125 => 125_000,
            Self::K100 => 100_000,
            Self::K50 => 50_000,
            Self::K20 => 20_000,
            Self::K10 => 10_000,
            Self::Auto => return None,
        })
    }

    /// The entry for `bits` bit/s, if the table has one.
    pub fn from_bits_per_second(bits: u32) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|t| t.bits_per_second() == Some(bits))
    }
}

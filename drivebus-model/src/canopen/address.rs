//! How a parameter is reached over CANopen: the protocol marker, object addresses and node ids.

use crate::Protocol;

/// The CANopen protocol marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CanOpen;

impl Protocol for CanOpen {
    type Address = ObjectAddress;
    const NAME: &'static str = "CANopen";
}

/// An object dictionary entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ObjectAddress {
    /// Object index.
    pub index: u16,
    /// Subindex.
    pub subindex: u8,
    /// Size in bytes on the wire (odd widths such as 3 for INTEGER24 included); 0 = variable.
    pub bytes: u16,
}

impl ObjectAddress {
    /// Entry `index`:`subindex`, `bytes` long on the wire (0 = variable).
    pub const fn new(index: u16, subindex: u8, bytes: u16) -> Self {
        Self {
            index,
            subindex,
            bytes,
        }
    }
}

/// A CANopen node id (1..=127).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct NodeId(pub u8);

impl NodeId {
    /// Lowest node id CiA 301 allows (0 addresses every node in NMT commands).
    pub const MIN: u8 = 1;
    /// Highest node id CiA 301 allows.
    pub const MAX: u8 = 127;

    /// The id if it lies in [`MIN`](Self::MIN)`..=`[`MAX`](Self::MAX).
    pub const fn new(id: u8) -> Option<Self> {
        if id >= Self::MIN && id <= Self::MAX {
            Some(Self(id))
        } else {
            None
        }
    }

    /// The raw id.
    pub const fn get(self) -> u8 {
        self.0
    }
}

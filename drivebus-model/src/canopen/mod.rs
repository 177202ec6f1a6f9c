//! CANopen vocabulary: object addresses and node ids, SDO abort codes, PDO mapping entries and
//! the SRDO configuration values (timing, COB-IDs, mapping checks).

pub mod abort;
mod address;
mod mapped_object;
pub mod srdo;

pub use abort::AbortCode;
pub use address::{CanOpen, NodeId, ObjectAddress};
pub use mapped_object::{mapping_bits, mapping_fits, MappedObject};

/// Highest 11-bit CAN identifier (COB-ID).
pub const MAX_COB_ID: u16 = 0x7FF;

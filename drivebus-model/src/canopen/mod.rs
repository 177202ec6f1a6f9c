//! CANopen vocabulary: object addresses and node ids, SDO abort codes, PDO mapping entries and
//! default COB-IDs, the SRDO configuration values (timing, COB-IDs, mapping checks).

pub mod abort;
mod address;
mod connection_set;
mod mapped_object;
mod pdo_setup;
pub mod srdo;

pub use abort::AbortCode;
pub use address::{CanOpen, NodeId, ObjectAddress};
pub use connection_set::predefined_pdo_cob_id;
pub use mapped_object::{mapping_bits, mapping_fits, MappedObject};
pub use pdo_setup::PdoKind;
#[cfg(feature = "alloc")]
pub use pdo_setup::PdoSetup;

/// Highest 11-bit CAN identifier (COB-ID).
pub const MAX_COB_ID: u16 = 0x7FF;

//! A PDO's configuration as data: which PDO, its COB-ID, its timing and its mapping. The
//! network file's checks produce it (`drivegen::network_file::check_pdos`) and the network
//! boot applies it (`drivebus::canopen::network::boot`, through `PdoConfig`).

#[cfg(feature = "alloc")]
use super::{predefined_pdo_cob_id, MappedObject};

/// Which way a PDO goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PdoKind {
    /// RPDO: master → node (0x1400.. / 0x1600..).
    Receive,
    /// TPDO: node → master (0x1800.. / 0x1A00..).
    Transmit,
}

/// One PDO to configure, owning its mapping (feature `alloc`).
#[cfg(feature = "alloc")]
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PdoSetup {
    /// RPDO or TPDO.
    pub kind: PdoKind,
    /// PDO number, 1..=512.
    pub number: u16,
    /// COB-ID without the "invalid" bit 31 (bit 30, no RTR, may be set).
    pub cob_id: u32,
    /// Transmission type (sub 2), if it is to be set.
    pub transmission_type: Option<u8>,
    /// Inhibit time in 100 µs (sub 3), if it is to be set.
    pub inhibit_time: Option<u16>,
    /// Event timer in ms (sub 5), if it is to be set.
    pub event_timer: Option<u16>,
    /// The mapped objects, in payload order.
    pub entries: alloc::vec::Vec<MappedObject>,
}

#[cfg(feature = "alloc")]
impl PdoSetup {
    /// The COB-ID PDO `number` of `node` has in the predefined connection set (CiA 301
    /// §7.3.5): PDOs 1-4; `None` for other numbers.
    pub const fn default_cob_id(kind: PdoKind, number: u16, node: u8) -> Option<u32> {
        predefined_pdo_cob_id(matches!(kind, PdoKind::Transmit), number, node)
    }
}

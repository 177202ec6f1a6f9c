//! The network file `drivegen network boot` reads (docs/network.md): the nodes of one CAN bus,
//! each with its description, expected identity, heartbeat, PDOs and boot parameters. Text to
//! [`NetworkFile`], every entry with the line it is on; [`check_pdos`] checks a node's PDOs
//! against its description (what the drive can map, and where). Resolving the descriptions
//! and checking the boot parameters is the CLI's.

mod error;
mod pdo_check;
mod read;
#[cfg(test)]
mod tests;

pub use error::{NetworkFileError, NetworkFileErrorKind};
pub use pdo_check::check_pdos;
pub use read::parse;

use crate::ir::Direction;

/// The version of the file format this module reads (`format = 1`).
pub const FORMAT_VERSION: u32 = 1;

/// A network: the nodes to boot, in the file's order.
#[derive(Debug, Clone, PartialEq)]
pub struct NetworkFile {
    /// The `[[node]]` entries.
    pub nodes: Vec<NodeEntry>,
}

/// One `[[node]]`.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeEntry {
    /// Its node id, 1-127.
    pub id: u8,
    /// Its description, as written (a path relative to the file, or absolute).
    pub description: String,
    /// The identity it must report (1018h sub 1-3); absent entries are not checked.
    pub identity: ExpectedIdentity,
    /// Its heartbeat producer time in ms (1017h), if one is to be set.
    pub heartbeat_ms: Option<u16>,
    /// Start it (NMT Start) once booted; default true.
    pub start: bool,
    /// The PDOs to configure at boot (`[[node.tpdo]]`, then `[[node.rpdo]]`, each in the
    /// file's order).
    pub pdos: Vec<PdoEntry>,
    /// The parameters to write at boot, in the file's order.
    pub parameters: Vec<BootParameter>,
    /// The line of its `[[node]]` (1-based).
    pub line: u32,
}

/// The identity a node must report.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ExpectedIdentity {
    /// Vendor-ID.
    pub vendor_id: Option<u32>,
    /// Product code.
    pub product_code: Option<u32>,
    /// Revision number.
    pub revision: Option<u32>,
}

/// One boot parameter: a description parameter and its value as `drivegen write` takes it.
#[derive(Debug, Clone, PartialEq)]
pub struct BootParameter {
    /// The parameter's name in the description.
    pub name: String,
    /// The value (`2000 ms`, `velocity`, `raw:5`; a number is written as it stands).
    pub value: String,
    /// The line it is on (1-based).
    pub line: u32,
}

/// One `[[node.tpdo]]` or `[[node.rpdo]]`: a PDO configured at boot.
#[derive(Debug, Clone, PartialEq)]
pub struct PdoEntry {
    /// TPDO (the drive transmits) or RPDO (the drive receives).
    pub direction: Direction,
    /// PDO number, 1-512.
    pub number: u16,
    /// COB-ID (bit 30 may be set); absent: the predefined connection set's (PDOs 1-4).
    pub cob_id: Option<u32>,
    /// Transmission type (communication sub 2), if it is to be set.
    pub transmission_type: Option<u8>,
    /// Inhibit time in 100 µs (sub 3), if it is to be set.
    pub inhibit_time: Option<u16>,
    /// Event timer in ms (sub 5), if it is to be set.
    pub event_timer: Option<u16>,
    /// The mapped parameters by name, in payload order, each with its line.
    pub mapping: Vec<MappedName>,
    /// The line of its table (1-based).
    pub line: u32,
}

/// A parameter named in a PDO's `mapping`.
#[derive(Debug, Clone, PartialEq)]
pub struct MappedName {
    /// The parameter's name in the description.
    pub name: String,
    /// The line it is on (1-based).
    pub line: u32,
}

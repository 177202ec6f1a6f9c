//! PDO mappings a description declares: which objects a PDO carries, in which order, under which
//! COB-ID. The generated crate turns each into a typed struct.

use serde::Serialize;

use super::{Citation, DataType};
use crate::diagnostic::Span;

/// Which way a PDO goes, seen from the drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PdoDirection {
    /// Transmit PDO: the drive sends it (mapping objects 0x1A00..).
    Tx,
    /// Receive PDO: the drive receives it (mapping objects 0x1600..).
    Rx,
}

/// A COB-ID, kept relative to the node id where the description says so.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct CobId {
    /// The value, or the offset added to the node id.
    pub value: u32,
    /// Whether the node id is added to `value`.
    pub plus_node_id: bool,
}

/// A declared PDO mapping.
#[derive(Debug, Clone, Serialize)]
pub struct PdoMapping {
    /// Name; the generated struct is its camel-case form.
    pub name: String,
    /// Documentation.
    pub doc: Option<String>,
    /// Transmit or receive.
    pub direction: PdoDirection,
    /// PDO number, 1..=512.
    pub number: u16,
    /// COB-ID of the PDO (bit 30, no RTR, may be set; bit 31 is `enabled`), if the description
    /// gives one (a PDO disabled by default may leave it to the user).
    pub cob_id: Option<CobId>,
    /// Whether the PDO is valid by default (COB-ID bit 31 clear).
    pub enabled: bool,
    /// Transmission type (communication object sub-index 2), if the description gives one.
    pub transmission_type: Option<u8>,
    /// Inhibit time (communication object sub-index 3, raw), if the description gives one.
    pub inhibit_time: Option<u16>,
    /// Event timer (communication object sub-index 5, raw), if the description gives one.
    pub event_timer: Option<u16>,
    /// The mapped parameters, in payload order.
    pub entries: Vec<String>,
    /// Where the mapping is documented.
    pub source: Option<Citation>,
    /// Span of the name.
    #[serde(skip)]
    pub span: Span,
    /// Span of the entry list.
    #[serde(skip)]
    pub entries_span: Span,
}

impl PdoMapping {
    /// The COB-ID the communication object holds by default, relative to the node id where the
    /// description says so: bit 31 set for a PDO disabled by default; without a declared COB-ID
    /// only bit 31 (not valid, no identifier assigned).
    pub fn default_cob_id(&self) -> CobId {
        let invalid = if self.enabled { 0 } else { 0x8000_0000 };
        match self.cob_id {
            Some(c) => CobId {
                value: c.value | invalid,
                plus_node_id: c.plus_node_id,
            },
            None => CobId {
                value: 0x8000_0000,
                plus_node_id: false,
            },
        }
    }
}

/// Bits a value of `data_type` takes in a PDO: one for a boolean, its bytes otherwise.
pub fn pdo_bits(data_type: DataType) -> u32 {
    match data_type {
        DataType::Bool => 1,
        other => u32::from(other.bytes()) * 8,
    }
}

impl super::Parameter {
    /// The object a PDO maps for this parameter: its CANopen address valid in every variant.
    pub fn pdo_object(&self) -> Option<&super::ObjectAddress> {
        self.canopen.iter().find(|a| a.variant.is_none())
    }
}

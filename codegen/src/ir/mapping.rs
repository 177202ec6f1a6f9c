//! Mappings a description declares: PDOs (`[[pdo]]`, CiA 301) and SRDOs (`[[srdo]]`, CANopen
//! Safety, EN 50325-5) are one concept: an ordered list of parameters packed into a CAN frame,
//! under a communication object that sets its identifiers and timing. The generated crate turns
//! each into a typed struct; only the communication defaults differ by kind.

use drivebus_model::canopen::MappedObject;

use super::{Citation, DataType, Device};
use crate::diagnostic::Span;

/// Which way a mapping goes, seen from the drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// The drive transmits it (TPDO, mapping objects 0x1A00..; a transmitted SRDO).
    Tx,
    /// The drive receives it (RPDO, mapping objects 0x1600..; a received SRDO).
    Rx,
}

/// A declared PDO or SRDO. Its JSON keeps the shape of its kind (`docs/ir-json.md`, "PDO
/// mapping" and "SRDO"; see `mapping_json.rs`).
#[derive(Debug, Clone)]
pub struct Mapping {
    /// Name; the generated struct is its camel-case form.
    pub name: String,
    /// Documentation.
    pub doc: Option<String>,
    /// Transmitted or received by the drive.
    pub direction: Direction,
    /// Whether it is valid by default (a PDO's COB-ID bit 31 clear; an SRDO's information
    /// direction non-zero).
    pub enabled: bool,
    /// Transmission type (PDO communication sub-index 2, SRDO sub-index 4), if the description
    /// gives one.
    pub transmission_type: Option<u8>,
    /// The mapped parameters in mapping-object order: payload order for a PDO; normal, inverted,
    /// normal, inverted, ... for an SRDO.
    pub entries: Vec<String>,
    /// Where it is documented.
    pub source: Option<Citation>,
    /// What differs by kind: the number and the communication defaults.
    pub kind: MappingKind,
    /// Span of the name.
    pub span: Span,
    /// Span of the entry list.
    pub entries_span: Span,
}

/// The kind of a mapping, with what only that kind has.
#[derive(Debug, Clone)]
pub enum MappingKind {
    /// A process data object (`[[pdo]]`).
    Pdo(PdoDefaults),
    /// A safety-related data object (`[[srdo]]`).
    Srdo(SrdoDefaults),
}

/// A PDO's number and communication defaults.
#[derive(Debug, Clone)]
pub struct PdoDefaults {
    /// PDO number, 1..=512 per direction.
    pub number: u16,
    /// COB-ID of the PDO (bit 30, no RTR, may be set; bit 31 is `enabled`), if the description
    /// gives one (a PDO disabled by default may leave it to the user).
    pub cob_id: Option<CobId>,
    /// Inhibit time (communication object sub-index 3, raw), if the description gives one.
    pub inhibit_time: Option<u16>,
    /// Event timer (communication object sub-index 5, raw), if the description gives one.
    pub event_timer: Option<u16>,
}

/// An SRDO's number and communication defaults.
#[derive(Debug, Clone)]
pub struct SrdoDefaults {
    /// SRDO number, 1..=64 (communication object 1300h + number, mapping 1380h + number).
    pub number: u8,
    /// Safeguard cycle time, ms.
    pub sct_ms: u16,
    /// SRDO valid time, ms.
    pub srvt_ms: u16,
    /// COB-IDs of the normal and the inverted frame.
    pub cob_ids: [SrdoCobId; 2],
    /// A decision where the manual contradicts itself.
    pub erratum: Option<String>,
}

/// A PDO COB-ID, kept relative to the node id where the description says so.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct CobId {
    /// The value, or the offset added to the node id.
    pub value: u32,
    /// Whether the node id is added to `value`.
    pub plus_node_id: bool,
}

/// An SRDO COB-ID: `base + node_id_factor × node-ID` (factor 0: the same on every node).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct SrdoCobId {
    /// The value on node 0, or the fixed value.
    pub base: u32,
    /// How many times the node-ID is added.
    pub node_id_factor: u32,
}

impl SrdoCobId {
    /// The COB-ID on `node_id`; `None` if it depends on the node-ID and none is given.
    pub fn resolve(&self, node_id: Option<u8>) -> Option<u32> {
        if self.node_id_factor == 0 {
            return Some(self.base);
        }
        node_id.map(|n| self.base + self.node_id_factor * u32::from(n))
    }
}

impl Mapping {
    /// `"PDO"` or `"SRDO"`, as messages and documents name the kind.
    pub fn label(&self) -> &'static str {
        match self.kind {
            MappingKind::Pdo(_) => "PDO",
            MappingKind::Srdo(_) => "SRDO",
        }
    }

    /// The PDO or SRDO number.
    pub fn number(&self) -> u16 {
        match &self.kind {
            MappingKind::Pdo(p) => p.number,
            MappingKind::Srdo(s) => u16::from(s.number),
        }
    }

    /// The PDO defaults, if it is a PDO.
    pub fn pdo(&self) -> Option<&PdoDefaults> {
        match &self.kind {
            MappingKind::Pdo(p) => Some(p),
            MappingKind::Srdo(_) => None,
        }
    }

    /// The SRDO defaults, if it is an SRDO.
    pub fn srdo(&self) -> Option<&SrdoDefaults> {
        match &self.kind {
            MappingKind::Srdo(s) => Some(s),
            MappingKind::Pdo(_) => None,
        }
    }

    /// The communication and mapping object indices: 0x1400/0x1800 and 0x1600/0x1A00 + number − 1
    /// for a PDO, 0x1300 and 0x1380 + number for an SRDO; `None` for a number outside the kind's
    /// range (only in a device no check has seen).
    pub fn object_indices(&self) -> Option<(u16, u16)> {
        match (&self.kind, self.direction) {
            (MappingKind::Pdo(p), direction) => {
                let offset = p.number.checked_sub(1).filter(|&o| o < 512)?;
                Some(match direction {
                    Direction::Rx => (0x1400 + offset, 0x1600 + offset),
                    Direction::Tx => (0x1800 + offset, 0x1A00 + offset),
                })
            }
            (MappingKind::Srdo(s), _) => {
                let number = u16::from(s.number);
                (1..=64)
                    .contains(&number)
                    .then_some((0x1300 + number, 0x1380 + number))
            }
        }
    }

    /// The information direction value an SRDO's communication sub-index 1 holds by default:
    /// 0 disabled, 1 transmitted, 2 received.
    pub fn information_direction(&self) -> u8 {
        match (self.enabled, self.direction) {
            (false, _) => 0,
            (true, Direction::Tx) => 1,
            (true, Direction::Rx) => 2,
        }
    }

    /// The PDO COB-ID the communication object holds by default, relative to the node id where
    /// the description says so: bit 31 set for a PDO disabled by default; without a declared
    /// COB-ID only bit 31 (not valid, no identifier assigned). `None` for an SRDO.
    pub fn default_cob_id(&self) -> Option<CobId> {
        let pdo = self.pdo()?;
        let invalid = if self.enabled { 0 } else { 0x8000_0000 };
        Some(match pdo.cob_id {
            Some(c) => CobId {
                value: c.value | invalid,
                plus_node_id: c.plus_node_id,
            },
            None => CobId {
                value: 0x8000_0000,
                plus_node_id: false,
            },
        })
    }

    /// The mapping object's entries (index, sub-index, bits), if every entry names a parameter
    /// with a CANopen object valid in every variant and a width a mapping entry can hold (what
    /// `mapping_entries_are_mappable` checks).
    pub fn mapped_objects(&self, device: &Device) -> Option<Vec<MappedObject>> {
        self.entries
            .iter()
            .map(|name| {
                let parameter = device.parameter(name)?;
                let object = parameter.pdo_object()?;
                let bits = u8::try_from(pdo_bits(parameter.data_type)).ok()?;
                Some(MappedObject::new(object.index, object.subindex, bits))
            })
            .collect()
    }
}

impl Device {
    /// The declared PDOs, with their defaults.
    pub fn pdos(&self) -> impl Iterator<Item = (&Mapping, &PdoDefaults)> {
        self.mappings.iter().filter_map(|m| Some((m, m.pdo()?)))
    }

    /// The declared SRDOs, with their defaults.
    pub fn srdos(&self) -> impl Iterator<Item = (&Mapping, &SrdoDefaults)> {
        self.mappings.iter().filter_map(|m| Some((m, m.srdo()?)))
    }
}

/// Bits a value of `data_type` takes in a PDO or SRDO: one for a boolean, its bytes otherwise.
pub fn pdo_bits(data_type: DataType) -> u32 {
    match data_type {
        DataType::Bool => 1,
        other => u32::from(other.bytes()) * 8,
    }
}

impl super::Parameter {
    /// The object a PDO or SRDO maps for this parameter: its CANopen address valid in every
    /// variant.
    pub fn pdo_object(&self) -> Option<&super::ObjectAddress> {
        self.canopen.iter().find(|a| a.variant.is_none())
    }
}

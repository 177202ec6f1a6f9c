//! SRDOs a description declares (CANopen Safety, EN 50325-5): number, default communication
//! parameters and mapping. The generated crate turns each into a typed struct; the CLI computes
//! its safety signature.

use serde::Serialize;

use super::{Citation, PdoDirection};
use crate::diagnostic::Span;

/// An SRDO COB-ID: `base + node_id_factor × node-ID` (factor 0: the same on every node).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
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

/// A declared SRDO.
#[derive(Debug, Clone, Serialize)]
pub struct SrdoMapping {
    /// Name; the generated struct is its camel-case form.
    pub name: String,
    /// Documentation.
    pub doc: Option<String>,
    /// SRDO number, 1..=64 (communication object 1300h + number, mapping 1380h + number).
    pub number: u8,
    /// Whether the drive transmits or receives it.
    pub direction: PdoDirection,
    /// Whether it is valid by default (information direction non-zero).
    pub enabled: bool,
    /// Safeguard cycle time, ms.
    pub sct_ms: u16,
    /// SRDO valid time, ms.
    pub srvt_ms: u16,
    /// Transmission type, if the description gives one.
    pub transmission_type: Option<u8>,
    /// COB-IDs of the normal and the inverted frame.
    pub cob_ids: [SrdoCobId; 2],
    /// The mapped parameters in mapping-object order: normal, inverted, normal, inverted, ...
    pub entries: Vec<String>,
    /// Where the SRDO is documented.
    pub source: Option<Citation>,
    /// A decision where the manual contradicts itself.
    pub erratum: Option<String>,
    /// Span of the name.
    #[serde(skip)]
    pub span: Span,
    /// Span of the entry list.
    #[serde(skip)]
    pub entries_span: Span,
}

impl SrdoMapping {
    /// The information direction value (sub-index 1) by default: 0 disabled, 1 TX, 2 RX.
    pub fn information_direction(&self) -> u8 {
        match (self.enabled, self.direction) {
            (false, _) => 0,
            (true, PdoDirection::Tx) => 1,
            (true, PdoDirection::Rx) => 2,
        }
    }
}

impl SrdoMapping {
    /// The mapping object's entries (index, sub-index, bits), if every entry names a parameter
    /// with a CANopen object valid in every variant (what `srdo_entries_are_mappable` checks).
    pub fn mapped_objects(
        &self,
        device: &super::Device,
    ) -> Option<Vec<drivebus_model::canopen::MappedObject>> {
        self.entries
            .iter()
            .map(|name| {
                let parameter = device.parameter(name)?;
                let object = parameter.pdo_object()?;
                let bits = u8::try_from(super::pdo_bits(parameter.data_type)).ok()?;
                Some(drivebus_model::canopen::MappedObject::new(
                    object.index,
                    object.subindex,
                    bits,
                ))
            })
            .collect()
    }
}

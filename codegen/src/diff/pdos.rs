//! Changes to declared PDO mappings: their structs, fields and wire identity.

use super::mappings::{self, MappingKind};
use super::Change;
use crate::ir::PdoMapping;

/// A removed mapping or changed entries change the generated struct (breaking); a new COB-ID,
/// number, transmission type, inhibit time or event timer only changes what goes on the wire.
pub(super) fn compare(old: &[PdoMapping], new: &[PdoMapping], out: &mut Vec<Change>) {
    let kind = MappingKind {
        subject: |m: &PdoMapping| format!("PDO `{}`", m.name),
        name: |m| &m.name,
        entries: |m| &m.entries,
        configuration: wire,
        consequence: "",
    };
    mappings::compare(&kind, old, new, out);
}

/// The communication configuration: what goes on the wire.
fn wire(m: &PdoMapping) -> String {
    let cob_id = m.default_cob_id();
    let base = if cob_id.plus_node_id {
        " + node id"
    } else {
        ""
    };
    format!(
        "{:?} {}, COB-ID 0x{:X}{base}, transmission type {:?}, inhibit time {:?}, event timer {:?}",
        m.direction, m.number, cob_id.value, m.transmission_type, m.inhibit_time, m.event_timer
    )
}

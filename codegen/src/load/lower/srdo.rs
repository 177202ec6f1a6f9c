//! Lowering of `[[srdo]]` tables: number, direction, times and COB-IDs are checked for form
//! here; what the entries name and how they pair is checked by the `srdo_*` validation passes.

use toml::Spanned;

use super::{Lowering, VALUE_RULE};
use crate::ir;
use crate::load::raw::RawFile;
use crate::load::raw_srdo::{RawSrdo, RawSrdoCobId};

impl Lowering<'_> {
    pub(super) fn srdo(&mut self, raw: &RawSrdo) -> Option<ir::SrdoMapping> {
        let number = self.srdo_number(&raw.number);
        let direction = self.srdo_direction(&raw.direction);
        let sct_ms = self.int_in::<u16>(&raw.sct_ms, "SCT (ms)");
        let srvt_ms = self.int_in::<u16>(&raw.srvt_ms, "SRVT (ms)");
        let transmission_type = match &raw.transmission_type {
            Some(t) => Some(self.int_in::<u8>(t, "transmission type")?),
            None => None,
        };
        let cob_ids = self.srdo_cob_ids(&raw.cob_ids);
        Some(ir::SrdoMapping {
            name: raw.name.get_ref().clone(),
            doc: raw.doc.clone(),
            number: number?,
            direction: direction?,
            enabled: raw.enabled.unwrap_or(true),
            sct_ms: sct_ms?,
            srvt_ms: srvt_ms?,
            transmission_type,
            cob_ids: cob_ids?,
            entries: raw.entries.get_ref().clone(),
            source: raw.source.as_ref().and_then(|s| self.citation(s)),
            erratum: raw.erratum.clone(),
            span: self.span(&raw.name),
            entries_span: self.span(&raw.entries),
        })
    }

    /// SRDOs belong to a drive, not to a shared profile.
    pub(super) fn refuse_included_srdos(&mut self, raw: &RawFile) {
        if let Some(first) = raw.srdo.first() {
            let span = self.span(&first.name);
            self.error_help(
                VALUE_RULE,
                span,
                "`[[srdo]]` in an included file",
                "declare SRDOs in the drive's own description (the root file)",
            );
        }
    }

    fn srdo_number(&mut self, raw: &Spanned<i64>) -> Option<u8> {
        if (1..=64).contains(raw.get_ref()) {
            return Some(*raw.get_ref() as u8);
        }
        let span = self.span(raw);
        self.error_help(
            VALUE_RULE,
            span,
            format!("SRDO number {} is out of range", raw.get_ref()),
            "EN 50325-5 numbers SRDOs 1..=64 (objects 1301h..1340h)",
        );
        None
    }

    fn srdo_direction(&mut self, raw: &Spanned<String>) -> Option<ir::PdoDirection> {
        match raw.get_ref().as_str() {
            "tx" => Some(ir::PdoDirection::Tx),
            "rx" => Some(ir::PdoDirection::Rx),
            other => {
                let span = self.span(raw);
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("unknown SRDO direction `{other}`"),
                    "use \"tx\" (the drive transmits) or \"rx\" (the drive receives); \
                     `enabled = false` for an SRDO invalid by default",
                );
                None
            }
        }
    }

    fn srdo_cob_ids(&mut self, raw: &Spanned<Vec<RawSrdoCobId>>) -> Option<[ir::SrdoCobId; 2]> {
        let span = self.span(raw);
        let ids: Vec<Option<ir::SrdoCobId>> = raw.get_ref().iter().map(srdo_cob_id).collect();
        match ids.as_slice() {
            [Some(normal), Some(inverted)] => Some([*normal, *inverted]),
            _ => {
                self.error_help(
                    VALUE_RULE,
                    span,
                    "`cob_ids` must be two SRDO COB-IDs: normal, then inverted",
                    "each is an 11-bit number or `{ base, node_id_factor }` for base + factor × node-ID",
                );
                None
            }
        }
    }
}

/// The COB-ID if it is 11 bits on every node (node-ID up to 127).
fn srdo_cob_id(raw: &RawSrdoCobId) -> Option<ir::SrdoCobId> {
    let (base, node_id_factor) = match raw {
        RawSrdoCobId::Number(n) => (*n, 0),
        RawSrdoCobId::NodeRelative(r) => (r.base, r.node_id_factor),
    };
    let base = u32::try_from(base).ok()?;
    let node_id_factor = u32::try_from(node_id_factor).ok()?;
    let highest = base.checked_add(node_id_factor.checked_mul(127)?)?;
    (highest <= 0x7FF).then_some(ir::SrdoCobId {
        base,
        node_id_factor,
    })
}

//! Lowering of `[[pdo]]` and `[[srdo]]` tables into one [`ir::Mapping`]: name, direction,
//! number and transmission type alike, then each kind's communication defaults (a PDO's COB-ID,
//! inhibit time and event timer; an SRDO's times and pair of COB-IDs). Values are checked for
//! form here; what the entries name is checked by the `mapping_*` validation passes.

use toml::Spanned;

use super::{Lowering, VALUE_RULE};
use crate::eds::node_id::{parse_value, EdsValue};
use crate::ir::{self, DataType, Number};
use crate::load::raw::RawFile;
use crate::load::raw_mapping::{RawCobId, RawMapping, RawPdoMapping, RawSrdo, RawSrdoCobId};

impl Lowering<'_> {
    /// The root file's PDOs, then its SRDOs; a table with an error is left out.
    pub(super) fn mappings(&mut self, raw: &RawFile) -> Vec<ir::Mapping> {
        let mut mappings = Vec::new();
        for pdo in &raw.pdo {
            let direction = self.direction(&pdo.direction, "PDO", PDO_DIRECTIONS);
            let kind = self.pdo(pdo).map(ir::MappingKind::Pdo);
            mappings.extend(self.mapping(pdo.shared(), direction, kind));
        }
        for srdo in &raw.srdo {
            let number = self.mapping_number(&srdo.number, "SRDO", 64, SRDO_NUMBERS);
            let direction = self.direction(&srdo.direction, "SRDO", SRDO_DIRECTIONS);
            let kind = self.srdo(srdo, number).map(ir::MappingKind::Srdo);
            mappings.extend(self.mapping(srdo.shared(), direction, kind));
        }
        mappings
    }

    /// PDOs and SRDOs belong to a drive, not to a shared profile: one in an included file would
    /// otherwise be dropped silently.
    pub(super) fn refuse_included_mappings(&mut self, raw: &RawFile) {
        let pdo = raw.pdo.first().map(|p| (&p.name, "pdo", "PDO mappings"));
        let srdo = raw.srdo.first().map(|s| (&s.name, "srdo", "SRDOs"));
        for (name, table, what) in pdo.into_iter().chain(srdo) {
            let span = self.span(name);
            self.error_help(
                VALUE_RULE,
                span,
                format!("`[[{table}]]` in an included file"),
                format!("declare {what} in the drive's own description (the root file)"),
            );
        }
    }

    /// What every mapping has, around its kind (`None` after an error in either).
    fn mapping(
        &mut self,
        raw: RawMapping<'_>,
        direction: Option<ir::Direction>,
        kind: Option<ir::MappingKind>,
    ) -> Option<ir::Mapping> {
        let transmission_type = match raw.transmission_type {
            Some(t) => Some(self.int_in::<u8>(t, "transmission type")?),
            None => None,
        };
        Some(ir::Mapping {
            name: raw.name.get_ref().clone(),
            doc: raw.doc.clone(),
            direction: direction?,
            enabled: raw.enabled,
            transmission_type,
            entries: raw.entries.get_ref().clone(),
            source: raw.source.and_then(|s| self.citation(s)),
            kind: kind?,
            span: self.span(raw.name),
            entries_span: self.span(raw.entries),
        })
    }

    fn direction(
        &mut self,
        raw: &Spanned<String>,
        label: &str,
        help: &str,
    ) -> Option<ir::Direction> {
        match raw.get_ref().as_str() {
            "tx" => Some(ir::Direction::Tx),
            "rx" => Some(ir::Direction::Rx),
            other => {
                let span = self.span(raw);
                let message = format!("unknown {label} direction `{other}`");
                self.error_help(VALUE_RULE, span, message, help);
                None
            }
        }
    }

    fn mapping_number(
        &mut self,
        raw: &Spanned<i64>,
        label: &str,
        highest: u16,
        help: &str,
    ) -> Option<u16> {
        let number = *raw.get_ref();
        if (1..=i64::from(highest)).contains(&number) {
            return u16::try_from(number).ok();
        }
        let span = self.span(raw);
        let message = format!("{label} number {number} is out of range");
        self.error_help(VALUE_RULE, span, message, help);
        None
    }

    fn pdo(&mut self, raw: &RawPdoMapping) -> Option<ir::PdoDefaults> {
        let number = self.mapping_number(&raw.number, "PDO", 512, PDO_NUMBERS);
        let cob_id = match &raw.cob_id {
            Some(c) => Some(self.cob_id(c)?),
            None => self.missing_cob_id(raw)?,
        };
        let inhibit_time = match &raw.inhibit_time {
            Some(t) => Some(self.int_in::<u16>(t, "inhibit time")?),
            None => None,
        };
        let event_timer = match &raw.event_timer {
            Some(t) => Some(self.int_in::<u16>(t, "event timer")?),
            None => None,
        };
        Some(ir::PdoDefaults {
            number: number?,
            cob_id,
            inhibit_time,
            event_timer,
        })
    }

    fn srdo(&mut self, raw: &RawSrdo, number: Option<u16>) -> Option<ir::SrdoDefaults> {
        let sct_ms = self.int_in::<u16>(&raw.sct_ms, "SCT (ms)");
        let srvt_ms = self.int_in::<u16>(&raw.srvt_ms, "SRVT (ms)");
        let cob_ids = self.srdo_cob_ids(&raw.cob_ids);
        Some(ir::SrdoDefaults {
            number: u8::try_from(number?).ok()?,
            sct_ms: sct_ms?,
            srvt_ms: srvt_ms?,
            cob_ids: cob_ids?,
            erratum: raw.erratum.clone(),
        })
    }

    /// A PDO without `cob_id`: allowed when it is disabled by default (the manual may not give
    /// the identifier of a PDO it ships disabled); `Some(None)` then, `None` after an error.
    fn missing_cob_id(&mut self, raw: &RawPdoMapping) -> Option<Option<ir::CobId>> {
        if !raw.shared().enabled {
            return Some(None);
        }
        let span = self.span(&raw.name);
        self.error_help(
            VALUE_RULE,
            span,
            format!(
                "PDO `{}` is enabled but has no `cob_id`",
                raw.name.get_ref()
            ),
            "give its `cob_id`, or declare it `enabled = false` if the drive ships it disabled",
        );
        None
    }

    fn cob_id(&mut self, raw: &Spanned<RawCobId>) -> Option<ir::CobId> {
        let parsed = match raw.get_ref() {
            RawCobId::Number(n) => Ok(EdsValue::Number(Number::Int(*n))),
            RawCobId::Text(text) => parse_value(text, DataType::Unsigned(4))
                .map(|v| v.expect("integers always have a value")),
        };
        let (value, plus_node_id) = match parsed {
            Ok(EdsValue::Number(Number::Int(v))) => (v, false),
            Ok(EdsValue::NodeIdPlus(offset)) => (offset, true),
            Ok(EdsValue::Number(Number::Float(_))) | Err(_) => (-1, false),
        };
        match u32::try_from(value) {
            Ok(value) if value & 0x8000_0000 == 0 => Some(ir::CobId {
                value,
                plus_node_id,
            }),
            _ => {
                let span = self.span(raw);
                self.error_help(
                    VALUE_RULE,
                    span,
                    "COB-ID is not a valid PDO COB-ID",
                    "write a number below 0x80000000 (bit 31 marks a disabled PDO) or \"$NODEID+0x180\"",
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

const PDO_DIRECTIONS: &str =
    "use \"tx\" (the drive transmits: TPDO) or \"rx\" (the drive receives: RPDO)";
const SRDO_DIRECTIONS: &str = "use \"tx\" (the drive transmits) or \"rx\" (the drive receives); \
                               `enabled = false` for an SRDO invalid by default";
const PDO_NUMBERS: &str = "CiA 301 numbers PDOs 1..=512 per direction";
const SRDO_NUMBERS: &str = "EN 50325-5 numbers SRDOs 1..=64 (objects 1301h..1340h)";

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

//! Lowering of `[[pdo]]` mapping tables: direction, number, COB-ID (absolute or node-relative)
//! and transmission type are checked for form here; what the entries name is checked by the
//! `pdo_*` validation passes.

use toml::Spanned;

use super::{Lowering, VALUE_RULE};
use crate::eds::node_id::{parse_value, EdsValue};
use crate::ir::{self, DataType, Number};
use crate::load::raw::*;

impl Lowering<'_> {
    pub(super) fn pdo_mapping(&mut self, raw: &RawPdoMapping) -> Option<ir::PdoMapping> {
        let direction = self.pdo_direction(&raw.direction);
        let number = self.pdo_number(&raw.number);
        let enabled = raw.enabled.as_ref().is_none_or(|e| *e.get_ref());
        let cob_id = match &raw.cob_id {
            Some(c) => Some(self.cob_id(c)?),
            None => self.missing_cob_id(raw, enabled)?,
        };
        let transmission_type = match &raw.transmission_type {
            Some(t) => Some(self.int_in::<u8>(t, "transmission type")?),
            None => None,
        };
        let inhibit_time = match &raw.inhibit_time {
            Some(t) => Some(self.int_in::<u16>(t, "inhibit time")?),
            None => None,
        };
        let event_timer = match &raw.event_timer {
            Some(t) => Some(self.int_in::<u16>(t, "event timer")?),
            None => None,
        };
        Some(ir::PdoMapping {
            name: raw.name.get_ref().clone(),
            doc: raw.doc.clone(),
            direction: direction?,
            number: number?,
            cob_id,
            enabled,
            transmission_type,
            inhibit_time,
            event_timer,
            entries: raw.entries.get_ref().clone(),
            source: raw.source.as_ref().and_then(|s| self.citation(s)),
            span: self.span(&raw.name),
            entries_span: self.span(&raw.entries),
        })
    }

    /// PDO mappings belong to a drive, not to a shared profile: one in an included file would
    /// otherwise be dropped silently.
    pub(super) fn refuse_included_pdos(&mut self, raw: &RawFile) {
        if let Some(first) = raw.pdo.first() {
            let span = self.span(&first.name);
            self.error_help(
                VALUE_RULE,
                span,
                "`[[pdo]]` in an included file",
                "declare PDO mappings in the drive's own description (the root file)",
            );
        }
    }

    fn pdo_direction(&mut self, raw: &Spanned<String>) -> Option<ir::PdoDirection> {
        match raw.get_ref().as_str() {
            "tx" => Some(ir::PdoDirection::Tx),
            "rx" => Some(ir::PdoDirection::Rx),
            other => {
                let span = self.span(raw);
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("unknown PDO direction `{other}`"),
                    "use \"tx\" (the drive transmits: TPDO) or \"rx\" (the drive receives: RPDO)",
                );
                None
            }
        }
    }

    fn pdo_number(&mut self, raw: &Spanned<i64>) -> Option<u16> {
        if (1..=512).contains(raw.get_ref()) {
            return Some(*raw.get_ref() as u16);
        }
        let span = self.span(raw);
        self.error_help(
            VALUE_RULE,
            span,
            format!("PDO number {} is out of range", raw.get_ref()),
            "CiA 301 numbers PDOs 1..=512 per direction",
        );
        None
    }

    /// A PDO without `cob_id`: allowed when it is disabled by default (the manual may not give
    /// the identifier of a PDO it ships disabled); `Some(None)` then, `None` after an error.
    fn missing_cob_id(&mut self, raw: &RawPdoMapping, enabled: bool) -> Option<Option<ir::CobId>> {
        if !enabled {
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
}

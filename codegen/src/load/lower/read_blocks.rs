//! Lowering of `[modbus] read_blocks`: the table, address and word count of each block are checked
//! for form here; that a block covers described, readable registers is the rule
//! `read_blocks_are_described`.

use toml::Spanned;

use super::{Lowering, VALUE_RULE};
use crate::ir;
use crate::load::raw::RawReadBlock;

/// Most registers one read request can carry (FC 0x03 / 0x04).
const MAX_READ: i64 = 125;

impl Lowering<'_> {
    pub(super) fn read_block(&mut self, raw: &Spanned<RawReadBlock>) -> Option<ir::ReadBlock> {
        let span = self.span(raw);
        let block = raw.get_ref();
        let table = match block.table.as_str() {
            "input" => ir::Table::Input,
            "holding" => ir::Table::Holding,
            other => {
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("unknown Modbus table `{other}`"),
                    "use \"input\" or \"holding\"",
                );
                return None;
            }
        };
        let spanned = |v: i64| Spanned::new(span.range.clone(), v);
        let address = self.int_in::<u16>(&spanned(block.address), "block address")?;
        if !(2..=MAX_READ).contains(&block.words) {
            self.error_help(
                VALUE_RULE,
                span,
                format!("a read block of {} words", block.words),
                "a block reads 2..=125 registers; a single register needs no block",
            );
            return None;
        }
        Some(ir::ReadBlock {
            table,
            address,
            words: block.words as u16,
            zero_fill: block.zero_fill.unwrap_or(false),
            source: block.source.as_ref().and_then(|c| self.citation(c)),
            span,
        })
    }
}

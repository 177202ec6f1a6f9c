//! Read blocks: reads a device answers although they exceed `max_read_registers`, exactly as
//! described (Lenze smd: "register #24 ... can also be read as a group of 6 words", covering
//! #24-#29 which are described one by one).

use serde::Serialize;

use super::{Citation, Table};
use crate::diagnostic::Span;

/// One read request the device answers beyond its general read limit.
#[derive(Debug, Clone, Serialize)]
pub struct ReadBlock {
    /// Table.
    pub table: Table,
    /// First register.
    pub address: u16,
    /// Registers read.
    pub words: u16,
    /// Whether registers of the block that no parameter occupies are answered (as 0): the
    /// manual reads a value with more registers than it has (Kinco FD: the 16-bit statusword
    /// read as 2 registers, line 2488).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub zero_fill: bool,
    /// Citation.
    pub source: Option<Citation>,
    /// Where it is declared.
    #[serde(skip)]
    pub span: Span,
}

impl ReadBlock {
    /// Whether the block is the read of `count` registers of `table` from `start`.
    pub fn is(&self, table: Table, start: u16, count: u16) -> bool {
        (self.table, self.address, self.words) == (table, start, count)
    }

    /// The registers the block covers.
    pub fn registers(&self) -> std::ops::Range<u32> {
        u32::from(self.address)..u32::from(self.address) + u32::from(self.words)
    }
}

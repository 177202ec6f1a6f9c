//! Reads a device answers beyond its `max_read_registers`, as the description states them: the
//! `[modbus] read_blocks` (Lenze smd: 6 words at #24), and the words of one value read at its
//! address (Lenze smd C99: 4 words at one register, `occupies = 1`); a `zero_fill` block also
//! answers registers no parameter occupies, as 0 (Kinco FD: the statusword read as 2 registers).

use drivebus::modbus::Table;
use drivegen::ir::ModbusCaps;

use super::map::{self, RegisterMap};
use crate::drive::Drive;

/// Whether `caps` lists the read of `count` registers of `table` from `start` as a block.
pub fn is_block(caps: Option<&ModbusCaps>, wire: Table, start: u16, count: u16) -> bool {
    caps.is_some_and(|c| {
        c.read_blocks
            .iter()
            .any(|b| b.table == wire && b.address == start && b.words == count)
    })
}

/// Whether `caps` lists the read as a `zero_fill` block: its registers no parameter occupies
/// answer 0 (Kinco FD: the statusword read as 2 registers, manual line 2488).
pub fn is_zero_fill(caps: Option<&ModbusCaps>, wire: Table, start: u16, count: u16) -> bool {
    caps.is_some_and(|c| {
        c.read_blocks
            .iter()
            .any(|b| b.zero_fill && b.table == wire && b.address == start && b.words == count)
    })
}

/// The registers of the one readable value of `count` words at `start`, if the read is exactly
/// that value.
pub fn whole_value(
    map: &RegisterMap,
    drive: &Drive,
    wire: Table,
    start: u16,
    count: u16,
) -> Option<Vec<u16>> {
    let cell = map.cell(wire, start)?;
    (cell.first == start && cell.words == count && cell.access.read)
        .then(|| map::registers(drive.store(), cell))
}

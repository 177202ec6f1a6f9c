//! Several commands on one command register (Lenze smd #1: start, stop, forward, ... each a
//! command parameter with its own trigger value): a write goes to the command whose value it is.

use drivegen::ir::Table;

use super::map::Cell;
use crate::store::Store;

/// The cell a write of `value` to holding register `address` goes to: another command sharing
/// the register when `value` is that command's trigger, else `cell` itself.
pub fn matching(store: &Store, cell: Cell, address: u16, value: u16) -> Cell {
    let own = store
        .parameter(cell.id)
        .command
        .as_ref()
        .and_then(|c| c.value);
    if own.is_none() || own == Some(i64::from(value)) {
        return cell;
    }
    store
        .device()
        .parameters
        .iter()
        .enumerate()
        .find(|(_, p)| {
            p.command.as_ref().and_then(|c| c.value) == Some(i64::from(value))
                && p.modbus
                    .iter()
                    .any(|a| a.table == Table::Holding && a.address == address && a.access.write)
        })
        .map_or(cell, |(id, _)| Cell { id, ..cell })
}

//! Several commands on one command register (Lenze smd #1: start, stop, forward, ... each a
//! command parameter with its own trigger value): a write goes to the command whose value it is;
//! a write setting several commands' bits follows `[modbus] combined_commands`.

use drivegen::ir::{ModbusCaps, Table};

use super::map::Cell;
use crate::store::Store;

/// The value a write of `value` to holding register `address` stands for under the device's
/// `combined_commands` rule: a value setting several bits that includes the bits of the command
/// the device `obeys` is that command alone; one without them is refused with the rule's
/// exception code. Any other write stands for itself.
pub fn combined(
    store: &Store,
    caps: Option<&ModbusCaps>,
    address: u16,
    value: u16,
) -> Result<u16, u8> {
    let Some(rule) = caps
        .and_then(|c| c.combined_commands.as_ref())
        .filter(|r| r.address == address)
    else {
        return Ok(value);
    };
    let trigger = |p: &drivegen::ir::Parameter| p.command.as_ref().and_then(|c| c.value);
    let is_a_command = store
        .device()
        .parameters
        .iter()
        .filter(|p| {
            p.modbus
                .iter()
                .any(|a| a.table == Table::Holding && a.address == address)
        })
        .any(|p| trigger(p) == Some(i64::from(value)));
    if is_a_command || value.count_ones() < 2 {
        return Ok(value);
    }
    let obeyed = store
        .id(&rule.obeys)
        .and_then(|id| trigger(store.parameter(id)))
        .and_then(|v| u16::try_from(v).ok());
    match obeyed {
        Some(bits) if value & bits == bits => Ok(bits),
        _ => Err(rule.refusal),
    }
}

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

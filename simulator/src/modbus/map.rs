//! Where each Modbus register of a description lives: parameter, word, order, access.

use std::collections::HashMap;

use drivebus::modbus::{le_to_registers, registers_to_le, Table, WordOrder};
use drivegen::ir::{self, Access, Device};

use crate::raw;
use crate::refusal::Refusal;
use crate::store::{ParamId, Store};

/// One register of a parameter.
#[derive(Debug, Clone, Copy)]
pub struct Cell {
    /// The parameter.
    pub id: ParamId,
    /// Address of the parameter's first register.
    pub first: u16,
    /// Registers the parameter occupies.
    pub words: u16,
    /// Word order of multi-register values.
    pub order: WordOrder,
    /// Access through this table.
    pub access: Access,
}

/// The register map of a device.
#[derive(Debug, Clone, Default)]
pub struct RegisterMap {
    cells: HashMap<(Table, u16), Cell>,
}

impl RegisterMap {
    /// The registers of `device` in `variant` (addresses limited to other variants are left out).
    pub fn new(device: &Device, variant: Option<&str>) -> Self {
        let mut cells = HashMap::new();
        for (id, parameter) in device.parameters.iter().enumerate() {
            let addresses = parameter
                .modbus
                .iter()
                .filter(|a| a.variant.is_none() || a.variant.as_deref() == variant);
            for address in addresses {
                let cell = Cell {
                    id,
                    first: address.address,
                    words: address.words,
                    order: word_order(address.word_order),
                    access: address.access,
                };
                for word in 0..address.words {
                    let key = (table(address.table), address.address.wrapping_add(word));
                    cells.insert(key, cell);
                }
            }
        }
        Self { cells }
    }

    /// The cell at `address` of `table`.
    pub fn cell(&self, table: Table, address: u16) -> Option<Cell> {
        self.cells.get(&(table, address)).copied()
    }
}

/// The registers holding the parameter of `cell`, in wire order.
pub fn registers(store: &Store, cell: Cell) -> Vec<u16> {
    let wire = 2 * cell.words as usize;
    let data_type = store.parameter(cell.id).data_type;
    let mut bytes = match raw::to_int(data_type, store.bytes(cell.id)) {
        Some(value) => value.to_le_bytes()[..wire.min(16)].to_vec(),
        None => store.bytes(cell.id).to_vec(),
    };
    bytes.resize(wire, 0);
    let mut out = vec![0u16; cell.words as usize];
    le_to_registers(&bytes, cell.order, &mut out);
    out
}

/// The parameter bytes the registers `regs` (wire order) stand for; integers that do not fit the
/// parameter's type are refused.
pub fn parameter_bytes(store: &Store, cell: Cell, regs: &[u16]) -> Result<Vec<u8>, Refusal> {
    let parameter = store.parameter(cell.id);
    let mut wire = vec![0u8; 2 * regs.len()];
    registers_to_le(regs, cell.order, &mut wire);
    let Some((min, max)) = parameter.data_type.integer_bounds() else {
        wire.truncate(parameter.data_type.bytes() as usize);
        return Ok(wire);
    };
    let signed = matches!(parameter.data_type, ir::DataType::Signed(_));
    let wire_type = if signed {
        ir::DataType::Signed(wire.len().min(16) as u8)
    } else {
        ir::DataType::Unsigned(wire.len().min(16) as u8)
    };
    let value = raw::to_int(wire_type, &wire).ok_or(Refusal::WrongLength)?;
    if value > max {
        return Err(Refusal::TooHigh);
    }
    if value < min {
        return Err(Refusal::TooLow);
    }
    Ok(raw::from_int(parameter.data_type, value))
}

fn table(table: ir::Table) -> Table {
    match table {
        ir::Table::Input => Table::Input,
        ir::Table::Holding => Table::Holding,
    }
}

fn word_order(order: ir::WordOrder) -> WordOrder {
    match order {
        ir::WordOrder::HighFirst => WordOrder::HighFirst,
        ir::WordOrder::LowFirst => WordOrder::LowFirst,
    }
}

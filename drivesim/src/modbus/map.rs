//! Where each Modbus register of a description lives: parameter, word, order, access.

use std::collections::HashMap;

use drivebus::modbus::{Table, WordOrder};
use drivegen::ir::{Access, Device};

use crate::refusal::Refusal;
use crate::store::{ParamId, Store};
use drivebus::interpret::registers::{self, Unfit};

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
            if !crate::variant_selection::exists_in(parameter, variant) {
                continue;
            }
            // A read-back (`read_back_of`) is another parameter's register: that one answers.
            let addresses = parameter
                .modbus
                .iter()
                .filter(|a| a.read_back_of.is_none())
                .filter(|a| a.variant.is_none() || a.variant.as_deref() == variant);
            for address in addresses {
                let cell = Cell {
                    id,
                    first: address.address,
                    words: address.words,
                    order: address.word_order,
                    access: address.access,
                };
                for word in 0..address.occupies {
                    let key = (address.table, address.address.wrapping_add(word));
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
    let data_type = store.parameter(cell.id).data_type;
    registers::to_registers(data_type, store.bytes(cell.id), cell.words, cell.order)
}

/// The parameter bytes the registers `regs` (wire order) stand for; integers that do not fit the
/// parameter's type are refused.
pub fn parameter_bytes(store: &Store, cell: Cell, regs: &[u16]) -> Result<Vec<u8>, Refusal> {
    registers::from_registers(store.parameter(cell.id).data_type, regs, cell.order).map_err(
        |unfit| match unfit {
            Unfit::TooHigh => Refusal::TooHigh,
            Unfit::TooLow => Refusal::TooLow,
            Unfit::WrongLength => Refusal::WrongLength,
        },
    )
}

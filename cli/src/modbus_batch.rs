//! Several parameters over Modbus in the fewest requests the device allows: the planner groups
//! neighbouring registers within the described limits, and a client opened with
//! `--max-in-flight` above 1 sends the requests together.

use drivebus::modbus::planner::{check_item, plan};
use drivebus::modbus::{
    ModbusAddress, ModbusLimits, RegisterBus, RegisterRead, RegisterSpan, UnitId,
};
use drivebus::BusError;
use drivegen::ir::{self, Device};
use drivesim::registers;

const WRITE_MULTIPLE_REGISTERS: u8 = 0x10;

/// The device's Modbus limits as described; the specification's where it says nothing.
pub fn limits(device: &Device) -> ModbusLimits {
    device
        .modbus
        .as_ref()
        .map_or(ModbusLimits::SPEC, |m| ModbusLimits {
            max_read_registers: m.max_read_registers,
            max_write_registers: m.max_write_registers,
            write_multiple: m.functions.contains(&WRITE_MULTIPLE_REGISTERS),
            read_gaps: m.read_gaps,
            readable: if m.read_gaps {
                &[]
            } else {
                readable_registers(device)
            },
        })
}

/// The description's readable registers for the planner. Limits hold them as `'static` (as
/// generated crates do); a command opens one session, so leaking one list per run is bounded.
fn readable_registers(device: &Device) -> &'static [RegisterSpan] {
    let spans = device
        .readable_register_runs()
        .into_iter()
        .map(|run| RegisterSpan {
            table: registers::table(run.table),
            start: run.start,
            count: run.count,
        });
    Vec::leak(spans.collect())
}

/// The wire address of a described Modbus address.
pub fn wire_address(address: &ir::ModbusAddress) -> ModbusAddress {
    ModbusAddress {
        table: registers::table(address.table),
        address: address.address,
        words: address.words,
        word_order: registers::word_order(address.word_order),
    }
}

/// A batch read that failed: the first value it could not read, and why.
#[derive(Debug, PartialEq)]
pub struct Failure {
    /// Index of the value in the batch.
    pub value: usize,
    /// Why it could not be read.
    pub cause: BusError,
}

/// Reads the registers of every address (in wire order) with the fewest requests `limits`
/// allow, handed to the bus as one batch.
pub fn read_registers(
    bus: &mut dyn RegisterBus,
    unit: UnitId,
    limits: &ModbusLimits,
    addresses: &[ModbusAddress],
) -> Result<Vec<Vec<u16>>, Failure> {
    for (value, address) in addresses.iter().enumerate() {
        check_item(limits, address).map_err(|cause| Failure { value, cause })?;
    }
    let plan = plan(limits, addresses).map_err(|cause| Failure { value: 0, cause })?;
    let mut registers: Vec<Vec<u16>> = plan.iter().map(|r| vec![0; r.count.into()]).collect();
    let mut batch: Vec<RegisterRead> = plan
        .iter()
        .zip(&mut registers)
        .map(|(read, out)| RegisterRead::new(read.table, read.start, out))
        .collect();
    if let Err(cause) = bus.read_register_batch(unit, &mut batch) {
        let failed = plan.iter().zip(&batch).find(|(_, read)| !read.done);
        let value = failed
            .and_then(|(read, _)| addresses.iter().position(|a| read.offset_of(a).is_some()))
            .unwrap_or(0);
        return Err(Failure { value, cause });
    }
    drop(batch);
    let value_registers = |(value, address): (usize, &ModbusAddress)| {
        plan.iter()
            .zip(&registers)
            .find_map(|(read, regs)| {
                let at = read.offset_of(address)?;
                regs.get(at..at + usize::from(address.words))
            })
            .map(<[u16]>::to_vec)
            .ok_or(Failure {
                value,
                cause: BusError::Unsupported("the read plan does not cover this value"),
            })
    };
    addresses.iter().enumerate().map(value_registers).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use drivebus::memory::{MemoryBus, Request};
    use drivebus::modbus::{Table, WordOrder};

    fn input(address: u16, words: u16) -> ModbusAddress {
        ModbusAddress {
            table: Table::Input,
            address,
            words,
            word_order: WordOrder::LowFirst,
        }
    }

    fn bus() -> MemoryBus {
        let mut bus = MemoryBus::new();
        for a in 0x60..=0x70 {
            bus.set_register(Table::Input, a, a);
        }
        bus
    }

    #[test]
    fn neighbouring_values_are_one_request() {
        let mut bus = bus();
        let addresses = [input(0x70, 1), input(0x6B, 2), input(0x60, 1)];
        let values = read_registers(&mut bus, UnitId(1), &ModbusLimits::SPEC, &addresses);
        assert_eq!(values, Ok(vec![vec![0x70], vec![0x6B, 0x6C], vec![0x60]]));
        assert_eq!(
            bus.log(),
            [Request::Read {
                table: Table::Input,
                start: 0x60,
                count: 17
            }]
        );
    }

    #[test]
    fn a_failed_read_names_the_first_value_it_held() {
        let mut bus = bus();
        let one_at_a_time = ModbusLimits {
            max_read_registers: 2,
            ..ModbusLimits::SPEC
        };
        let addresses = [input(0x60, 1), input(0x71, 1)];
        let failure = read_registers(&mut bus, UnitId(1), &one_at_a_time, &addresses);
        assert_eq!(failure.unwrap_err().value, 1);
        let too_wide = [input(0x60, 1), input(0x61, 3)];
        let failure = read_registers(&mut bus, UnitId(1), &one_at_a_time, &too_wide);
        assert_eq!(
            failure,
            Err(Failure {
                value: 1,
                cause: BusError::Unsupported("value wider than the device's read limit")
            })
        );
    }
}

//! Several parameters over Modbus in the fewest requests the device allows: the link's planner
//! groups neighbouring registers within the described limits, and a client opened with
//! `--max-in-flight` above 1 sends the requests together.

use drivebus::link::{Link, ReadRequest};
use drivebus::modbus::planner::check_item;
use drivebus::modbus::{
    ModbusAddress, ModbusLimits, ModbusLink, RegisterBus, RegisterSpan, UnitId,
};
use drivebus::BusError;
use drivegen::ir::{self, Device};

/// The device's Modbus limits as described; the specification's where it says nothing.
pub fn limits(device: &Device) -> ModbusLimits {
    device
        .planner_limits()
        .map_or(ModbusLimits::SPEC, |limits| ModbusLimits {
            max_read_registers: limits.max_read_registers,
            max_write_registers: limits.max_write_registers,
            write_multiple: limits.write_multiple,
            read_gaps: limits.read_gaps,
            readable: register_spans(limits.readable),
            unreadable: register_spans(limits.unreadable),
            read_blocks: register_spans(limits.read_blocks),
            whole_values: register_spans(limits.whole_values),
        })
}

/// Register runs as limits hold them: `'static` (as generated crates do); a command opens one
/// session, so leaking four lists per run is bounded.
fn register_spans(runs: Vec<ir::RegisterRun>) -> &'static [RegisterSpan] {
    let spans = runs.into_iter().map(|run| RegisterSpan {
        table: run.table,
        start: run.start,
        count: run.count,
    });
    Vec::leak(spans.collect())
}

/// A batch read that failed: the first value it could not read, and why.
#[derive(Debug, PartialEq)]
pub struct Failure {
    /// Index of the value in the batch.
    pub value: usize,
    /// Why it could not be read.
    pub cause: BusError,
}

/// Reads the value of every address as the little-endian bytes of its registers, in its word
/// order, through [`ModbusLink::read_many`]: the fewest requests `limits` allow, handed to the
/// bus together.
pub fn read_wire(
    bus: &mut dyn RegisterBus,
    unit: UnitId,
    limits: ModbusLimits,
    addresses: &[ModbusAddress],
) -> Result<Vec<Vec<u8>>, Failure> {
    // Checked here first only to name the value at fault; the link checks them too.
    for (value, address) in addresses.iter().enumerate() {
        check_item(&limits, address).map_err(|cause| Failure { value, cause })?;
    }
    let mut wire: Vec<Vec<u8>> = addresses
        .iter()
        .map(|a| vec![0; 2 * usize::from(a.words)])
        .collect();
    let mut requests: Vec<ReadRequest<ModbusAddress>> = addresses
        .iter()
        .zip(&mut wire)
        .map(|(address, buf)| ReadRequest {
            address: *address,
            buf,
            len: 0,
        })
        .collect();
    if let Err(cause) = ModbusLink::new(bus, unit, limits).read_many(&mut requests) {
        // The link reads in (table, address) order, not in the order values were asked for: the
        // lowest unread address is the read that failed.
        let unread = (0..requests.len()).filter(|&i| requests[i].len == 0);
        let address = |i: &usize| (addresses[*i].table, addresses[*i].address);
        let value = unread.min_by_key(address).unwrap_or(0);
        return Err(Failure { value, cause });
    }
    Ok(wire)
}

#[cfg(test)]
mod tests {
    use super::*;
    use drivebus::memory::MemoryBus;
    use drivebus::modbus::{Table, WordOrder};

    fn input(address: u16, words: u16) -> ModbusAddress {
        ModbusAddress::input(address, words, WordOrder::LowFirst)
    }

    fn bus() -> MemoryBus {
        let mut bus = MemoryBus::new();
        for a in 0x60..=0x70 {
            bus.set_register(Table::Input, a, a);
        }
        bus
    }

    #[test]
    fn a_failed_read_names_the_first_value_it_held() {
        let mut bus = bus();
        let two_at_a_time = ModbusLimits {
            max_read_registers: 2,
            ..ModbusLimits::SPEC
        };
        let addresses = [input(0x60, 1), input(0x71, 1)];
        let failure = read_wire(&mut bus, UnitId(1), two_at_a_time, &addresses);
        assert_eq!(failure.unwrap_err().value, 1);
        // Reads go by address, not by the order values were asked for: the failing read of 0x50
        // leaves 0x60 unread too, yet 0x50 is named.
        let addresses = [input(0x60, 1), input(0x50, 1)];
        let failure = read_wire(&mut bus, UnitId(1), two_at_a_time, &addresses);
        assert_eq!(failure.unwrap_err().value, 1);
        let too_wide = [input(0x60, 1), input(0x61, 3)];
        let failure = read_wire(&mut bus, UnitId(1), two_at_a_time, &too_wide);
        assert_eq!(
            failure,
            Err(Failure {
                value: 1,
                cause: BusError::Unsupported("value wider than the device's read limit")
            })
        );
    }
}

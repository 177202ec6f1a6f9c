//! The described Modbus limits the link's planner obeys: registers per read, readable runs,
//! read blocks, whether FC 0x10 exists.

use drivebus::modbus::{ModbusLimits, RegisterSpan};
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

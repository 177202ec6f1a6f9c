use drivebus::modbus::{ModbusLimits, ModbusLink, UnitId};
use drivebus::testing::{now, Immediate, MemoryBus};
use drivebus::units::Volts;
use lafert_smartris::Smartris;

fn main() {
    let link = ModbusLink::new(MemoryBus::new(), UnitId(1), ModbusLimits::SPEC);
    let mut drive = Smartris::new_async(Immediate(link));
    // The async handle keeps the access rules: an input register is read-only.
    let _ = now(drive.bus_dc_link().write(Volts(48.0)));
}

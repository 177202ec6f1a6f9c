use drivebus::modbus::{ModbusLimits, ModbusLink, UnitId};
use drivebus::testing::{now, Immediate, MemoryBus};
use drivebus::units::Volts;
use lafert_smartris::Smartris;

fn main() {
    let link = ModbusLink::new(MemoryBus::new(), UnitId(1), ModbusLimits::SPEC);
    let mut drive = Smartris::new_async(Immediate(link));
    let _: Option<Result<Volts, _>> = now(drive.bus_dc_link().read());
}

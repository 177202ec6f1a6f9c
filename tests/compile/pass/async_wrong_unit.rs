use drivebus::modbus::{ModbusLimits, ModbusLink, UnitId};
use drivebus::testing::{now, Immediate, MemoryBus};
use drivebus::units::{Rpm, Volts};
use lafert_smartris::Smartris;

fn main() {
    let link = ModbusLink::new(MemoryBus::new(), UnitId(1), ModbusLimits::SPEC);
    let mut drive = Smartris::new_async(Immediate(link));
    let _ = now(drive.speed_setpoint().write(Rpm(1500.0)));
    let _ = Volts(0.0);
}

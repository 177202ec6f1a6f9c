use drivebus::modbus::{ModbusLimits, ModbusLink, UnitId};
use drivebus::testing::{now, Immediate, MemoryBus};
use drivebus::units::{Rpm, Volts};
use lafert_smartris::Smartris;

fn main() {
    let link = ModbusLink::new(MemoryBus::new(), UnitId(1), ModbusLimits::SPEC);
    let mut drive = Smartris::new_async(Immediate(link));
    // Volts where the setpoint takes rpm: the same error as the blocking handle gives.
    let _ = now(drive.speed_setpoint().write(Volts(1500.0)));
    let _ = Rpm(0.0);
}

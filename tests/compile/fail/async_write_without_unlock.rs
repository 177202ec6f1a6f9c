use drivebus::modbus::{ModbusLimits, ModbusLink, UnitId};
use drivebus::testing::{now, Immediate, MemoryBus};
use drivebus::units::Seconds;

fn main() {
    let link = ModbusLink::new(MemoryBus::new(), UnitId(10), ModbusLimits::SPEC);
    let mut drive = lenze_smd::LenzeSmd::new_async(Immediate(link));
    // C12 needs an unlock: the async handle reads it too, and has no setter either.
    let _ = now(drive.acceleration_time().write(Seconds(10.0)));
}

use drivebus::modbus::{ModbusLimits, ModbusLink, UnitId};
use drivebus::testing::{now, Immediate, MemoryBus};
use drivebus::units::Seconds;

fn main() {
    let link = ModbusLink::new(MemoryBus::new(), UnitId(10), ModbusLimits::SPEC);
    let mut drive = lenze_smd::LenzeSmd::new_async(Immediate(link));
    let _: Option<Result<Seconds, _>> = now(drive.acceleration_time().read());
}

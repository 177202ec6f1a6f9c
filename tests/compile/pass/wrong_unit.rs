use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use drivebus::units::Rpm;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::modbus(MemoryBus::new(), UnitId(1));
    let _ = drive.speed_setpoint().write(Rpm(1500.0));
}

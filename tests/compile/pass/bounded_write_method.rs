use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use drivebus::units::Rpm;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::modbus(MemoryBus::new(), UnitId(1));
    // Reads FULL SCALE VELOCITY first; beyond it, `drivebus::Error::OutsideBound`.
    let _: Result<(), drivebus::Error> = drive.speed_setpoint().write(Rpm(1500.0));
}

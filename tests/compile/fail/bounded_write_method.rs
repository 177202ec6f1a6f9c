use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use drivebus::units::Rpm;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::modbus(MemoryBus::new(), UnitId(1));
    // The bounded write is the accessor's own `write` now; there is no second method.
    let _ = drive.write_speed_setpoint(Rpm(1500.0));
}

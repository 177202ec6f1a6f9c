use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use lafert_smartris::params;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::modbus(MemoryBus::new(), UnitId(1));
    let _ = drive.read_many((params::BusDcLink, params::MotorTemperature));
}

use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::modbus(MemoryBus::new(), UnitId(1));
    let _ = drive.store_eeprom().write(1);
}

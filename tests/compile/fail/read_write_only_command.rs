use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::modbus(MemoryBus::new(), UnitId(1));
    // Store E2PROM is a command register: write-only.
    let _ = drive.store_eeprom().read();
}

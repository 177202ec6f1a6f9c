use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use lafert_smartris::types::BaudRate;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::modbus(MemoryBus::new(), UnitId(1));
    let _ = drive.baud_rate().write(BaudRate::try_from(96u16).unwrap());
}

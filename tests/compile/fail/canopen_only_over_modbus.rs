use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::modbus(MemoryBus::new(), UnitId(1));
    // The CiA 402 statusword is a CANopen object only.
    let _ = drive.statusword().read();
}

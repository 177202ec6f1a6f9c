use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use drivegen_tests::kinco_rs232::KincoRs232;

fn main() {
    let mut drive = KincoRs232::modbus(MemoryBus::new(), UnitId(1));
    let _ = drive.positioning_select().read();
}

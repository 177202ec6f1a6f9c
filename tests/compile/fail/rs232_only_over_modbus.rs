use drivebus::testing::MemoryBus;
use drivebus::modbus::UnitId;
use drivebus::units::Rpm;
use drivegen_tests::kinco_rs232::KincoRs232;

fn main() {
    let mut drive = KincoRs232::modbus(MemoryBus::new(), UnitId(1));
    // The target speed has no Modbus register in the fixture; RS-232 and CANopen reach it.
    let _ = drive.target_speed().write(Rpm(150.0));
}

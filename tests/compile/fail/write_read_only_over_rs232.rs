use drivebus::testing::MemoryBus;
use drivebus::rs232::StationId;
use drivegen_tests::kinco_rs232::KincoRs232;

fn main() {
    let mut drive = KincoRs232::rs232(MemoryBus::new(), StationId(1));
    // The statusword is read-only over RS-232.
    let _ = drive.statusword().write(0x000Fu16);
}

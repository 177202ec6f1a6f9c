use drivebus::testing::MemoryBus;
use drivebus::canopen::NodeId;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::canopen(MemoryBus::new(), NodeId(1));
    let _ = drive.statusword().read();
}

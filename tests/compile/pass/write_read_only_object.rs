use drivebus::testing::MemoryBus;
use drivebus::canopen::NodeId;
use lafert_smartris::types::Controlword;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::canopen(MemoryBus::new(), NodeId(1));
    let _ = drive.controlword().write(Controlword::empty());
}

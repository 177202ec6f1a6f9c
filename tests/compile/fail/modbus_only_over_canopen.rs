use drivebus::testing::MemoryBus;
use drivebus::canopen::NodeId;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::canopen(MemoryBus::new(), NodeId(1));
    // The DC link register has no CANopen object in the description.
    let _ = drive.bus_dc_link().read();
}

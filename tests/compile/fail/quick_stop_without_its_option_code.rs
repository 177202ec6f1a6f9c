use drivebus::canopen::NodeId;
use drivebus::testing::MemoryBus;
use lafert_smartris::Smartris;

fn main() {
    let mut drive = Smartris::canopen(MemoryBus::new(), NodeId(1));
    // The Lafert guide documents no quick stop option code (605Ah): the handle has `quick_stop`
    // but no `quick_stop_by_option_code`.
    let _ = drive.quick_stop(std::time::Instant::now());
    let _ = drive.quick_stop_by_option_code(std::time::Instant::now());
}

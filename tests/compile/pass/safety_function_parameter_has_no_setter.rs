use drivebus::canopen::NodeId;
use drivebus::testing::MemoryBus;

fn main() {
    let mut drive = ezwheel_swd::Swd::canopen(MemoryBus::new(), NodeId(0x10));
    // Reading 6607h is allowed.
    let _ = drive.safety_configuration_valid().read_raw();
}

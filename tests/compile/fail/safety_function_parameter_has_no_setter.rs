use drivebus::canopen::NodeId;
use drivebus::testing::MemoryBus;

fn main() {
    let mut drive = ezwheel_swd::Swd::canopen(MemoryBus::new(), NodeId(0x10));
    // 6607h "safety application configuration valid" (SWD manual line 3488) is a safety-function
    // parameter (`safety = true`): the generated API reads it but has no plain setter.
    let _ = drive.safety_configuration_valid().write_raw(0xA5);
}

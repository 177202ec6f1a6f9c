use drivebus::canopen::NodeId;
use drivebus::testing::MemoryBus;
use drivebus::units::Rpm;

fn main() {
    let mut drive = ezwheel_swd::Swd::canopen(MemoryBus::new(), NodeId(0x10));
    // 6693h SLS velocity limits (line 3399) are safety-function parameters: the indexed
    // accessor reads them but cannot write them.
    let _ = drive.sls_velocity_limit(3).write(Rpm(100.0));
}

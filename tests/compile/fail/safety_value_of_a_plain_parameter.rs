use drivebus::canopen::srdo::SafetyValue;
use drivebus::canopen::NodeId;
use drivebus::testing::MemoryBus;
use drivebus::units::Rpm;

fn main() {
    let mut drive = ezwheel_swd::Swd::canopen(MemoryBus::new(), NodeId(0x10));
    // 6042h vl target velocity is no safety-function parameter: it has a setter, and the
    // deliberate safety-function write does not take it.
    let _ = SafetyValue::of::<ezwheel_swd::params::VlTargetVelocity, _>(drive.device(), Rpm(100.0));
}

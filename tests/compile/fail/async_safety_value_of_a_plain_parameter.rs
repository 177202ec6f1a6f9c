use drivebus::canopen::srdo::SafetyValue;
use drivebus::canopen::NodeId;
use drivebus::testing::{now, Immediate, MemoryBus};
use drivebus::units::Rpm;

fn main() {
    let mut drive = ezwheel_swd::Swd::canopen_async(Immediate(MemoryBus::new()), NodeId(0x10));
    // 6042h vl target velocity is no safety-function parameter: on the async handle as on the
    // blocking one, the deliberate safety-function write does not take it.
    let _ = now(SafetyValue::of_async::<ezwheel_swd::params::VlTargetVelocity, _>(
        drive.device(),
        Rpm(100.0),
    ));
}

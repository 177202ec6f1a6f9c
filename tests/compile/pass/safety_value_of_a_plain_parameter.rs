use drivebus::canopen::srdo::SafetyValue;
use drivebus::canopen::NodeId;
use drivebus::testing::MemoryBus;
use drivebus::units::Rpm;

fn main() {
    let mut drive = ezwheel_swd::Swd::canopen(MemoryBus::new(), NodeId(0x10));
    // SLSa 3's positive velocity limit (3052h sub 3, `safety = true`) goes through it.
    let _ = SafetyValue::of::<drivebus::indexed::At<ezwheel_swd::params::SlsaPositiveVelocityLimitRun, 3>, _>(
        drive.device(),
        Rpm(100.0),
    );
    // 6042h keeps its plain setter.
    let _ = drive.vl_target_velocity().write(Rpm(100.0));
}

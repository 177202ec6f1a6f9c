use drivebus::canopen::nmt::NmtState;
use drivebus::canopen::srdo::SafetyValue;
use drivebus::canopen::NodeId;
use drivebus::testing::{now, Immediate, MemoryBus};
use drivebus::units::Rpm;
use ezwheel_swd::safety_functions::SLSA;

fn main() {
    let mut drive = ezwheel_swd::Swd::canopen_async(Immediate(MemoryBus::new()), NodeId(0x10));
    // SLSa 3's positive velocity limit (3052h sub 3, `safety = true`) goes through it.
    let limit = now(SafetyValue::of_async::<
        drivebus::indexed::At<ezwheel_swd::params::SlsaPositiveVelocityLimitRun, 3>,
        _,
    >(drive.device(), Rpm(100.0)));
    if let Some(Ok(limit)) = limit {
        let _ = now(drive.write_safety_function_async(NmtState::PreOperational, &SLSA, 3, &[limit]));
    }
    // 6042h keeps its plain setter.
    let _ = now(drive.vl_target_velocity().write(Rpm(100.0)));
}

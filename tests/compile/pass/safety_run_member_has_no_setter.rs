use drivebus::canopen::nmt::NmtState;
use drivebus::canopen::srdo::SafetyValue;
use drivebus::canopen::NodeId;
use drivebus::testing::MemoryBus;
use drivebus::units::Rpm;
use ezwheel_swd::safety_functions::SLS;

fn main() {
    let mut drive = ezwheel_swd::Swd::canopen(MemoryBus::new(), NodeId(0x10));
    let _ = drive.sls_velocity_limit(3).read();
    // The deliberate write: Pre-Operational, then SLS 3's signature.
    if let Ok(limit) =
        SafetyValue::of::<drivebus::indexed::At<ezwheel_swd::params::SlsVelocityLimitRun, 3>, _>(drive.device(), Rpm(100.0))
    {
        let _ = drive.write_safety_function(NmtState::PreOperational, &SLS, 3, &[limit]);
    }
}

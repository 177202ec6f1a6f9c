use drivebus::canopen::NodeId;
use drivebus::testing::MemoryBus;
use ezwheel_swd::Swd;

fn main() {
    let mut drive = Swd::canopen(MemoryBus::new(), NodeId(1));
    // The SWD runs velocity mode (vl) only: its description has no target velocity (60FFh) nor
    // target torque (6071h), so the handle has neither `run_at_velocity` nor `apply_torque`.
    let _ = drive.run_at_velocity(1_000, std::time::Instant::now());
    let _ = drive.apply_torque(10, std::time::Instant::now());
}

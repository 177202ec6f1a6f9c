use drivebus::canopen::NodeId;
use drivebus::testing::MemoryBus;
use kinco_fd::KincoFd;

fn main() {
    // The Kinco lists profile velocity (3) and torque (4) and describes 60FFh, 606Ch and 6071h:
    // the handle has `run_at_velocity` and `apply_torque`.
    let mut drive = KincoFd::canopen(MemoryBus::new(), NodeId(1));
    let _ = drive.run_at_velocity(1_000, std::time::Instant::now());
    let _ = drive.apply_torque(10, std::time::Instant::now());
}

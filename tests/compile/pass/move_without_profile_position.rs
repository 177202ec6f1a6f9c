use drivebus::canopen::NodeId;
use drivebus::control::position::Move;
use drivebus::testing::MemoryBus;
use kinco_fd::KincoFd;

fn main() {
    // The Kinco lists profile position and describes 607Ah and 6063h: the handle has `move_to`.
    let mut drive = KincoFd::canopen(MemoryBus::new(), NodeId(1));
    let _ = drive.move_to(Move::to(50_000), std::time::Instant::now());
}

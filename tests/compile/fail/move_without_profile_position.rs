use drivebus::canopen::NodeId;
use drivebus::control::position::Move;
use drivebus::testing::MemoryBus;
use ezwheel_swd::Swd;

fn main() {
    let mut drive = Swd::canopen(MemoryBus::new(), NodeId(1));
    // The SWD runs velocity mode only: its description has no target position (607Ah) and its
    // modes list no profile position, so the handle has no `move_to`.
    let _ = drive.move_to(Move::to(50_000), std::time::Instant::now());
}

use std::time::Duration;

use drivebus::asynch::TokioTimer;
use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::control::position::Move;
use drivebus::testing::{Immediate, MemoryBus};
use ezwheel_swd::Swd;

fn main() {
    let link = CanOpenLink::new(MemoryBus::new(), NodeId(1));
    let mut drive = Swd::new_async(Immediate(link));
    // The SWD runs velocity mode (vl) only: no target position (607Ah), target velocity (60FFh)
    // nor target torque (6071h), so the async handle has none of the motion methods.
    let _ = drive.move_to_async(Move::to(50_000), &TokioTimer, Duration::from_secs(1));
    let _ = drive.run_at_velocity_async(1_000, &TokioTimer, Duration::from_secs(1));
    let _ = drive.apply_torque_async(10, &TokioTimer, Duration::from_secs(1));
}

use std::time::Duration;

use drivebus::asynch::TokioTimer;
use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::control::position::Move;
use drivebus::testing::{Immediate, MemoryBus};
use kinco_fd::types::HomingMethod;
use kinco_fd::KincoFd;

fn main() {
    // The Kinco describes the objects of profile position, homing, profile velocity and torque:
    // the async handle has each motion method (each future made, not run: no runtime here).
    let link = CanOpenLink::new(MemoryBus::new(), NodeId(1));
    let mut drive = KincoFd::new_async(Immediate(link));
    drop(drive.move_to_async(Move::to(50_000), &TokioTimer, Duration::from_secs(1)));
    drop(drive.home_async(HomingMethod::METHOD17, &TokioTimer, Duration::from_secs(1)));
    drop(drive.run_at_velocity_async(1_000, &TokioTimer, Duration::from_secs(1)));
    drop(drive.apply_torque_async(10, &TokioTimer, Duration::from_secs(1)));
    drop(drive.quick_stop_by_option_code_async(&TokioTimer, Duration::from_secs(1)));
}

//! Homing and profile position moves on a Kinco FD through the typed motion API of the generated
//! `kinco-fd` crate (issue 32), against the simulated drive built from the same description on an
//! in-process CAN bus: home on the switch (method 17) with a home offset, then move to three
//! positions and print the position and the position error at each.
//!
//! ```sh
//! cargo run --example kinco_position
//! ```
//!
//! The Kinco manual gives no following error actual value (60F4h): the error printed is the
//! target minus the actual position once the drive reports target reached, which the position
//! window 6067h bounds. The simulator takes the drive's velocity units (DEC) as increments per
//! second, so the simulated moves are faster than a real motor's.

use std::error::Error;
use std::time::{Duration, Instant};

use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::NodeId;
use drivebus::control::position::Move;
use drivebus::units::{Increments, Rpm, RpsPerSecond};
use drivesim::canopen::{InProcessNode, NodeConfig};
use kinco_fd::types::HomingMethod;
use kinco_fd::KincoFd;

const DESCRIPTION: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/kinco-fd");
const POSITIONS: [i32; 3] = [50_000, -20_000, 120_000];

fn main() -> Result<(), Box<dyn Error>> {
    let sim = drivesim::Simulator::load(DESCRIPTION)?;
    // The simulated motor's encoder: the manual's examples assume 10000 increments.
    sim.preset("encoder_resolution", 10_000)?;
    let config = NodeConfig {
        node: NodeId(1),
        heartbeat: None,
    };
    let (endpoint, _node) = InProcessNode::start(sim, config);
    let sdo = BlockingSdo::new(endpoint).with_timeout(Duration::from_millis(500));
    let mut drive = KincoFd::canopen(sdo, NodeId(1));
    println!("CANopen, simulated Kinco FD as node 1 on an in-process bus");

    // Values the DEC conversion represents exactly at 10000 increments: 150 rpm = 409600 DEC,
    // 610.3515625 rps/s = 100000 DEC (the manual's default acceleration).
    drive.profile_speed().write(Rpm(150.0))?;
    drive
        .profile_acceleration()
        .write(RpsPerSecond(610.351_562_5))?;
    drive
        .profile_deceleration()
        .write(RpsPerSecond(610.351_562_5))?;
    drive.homing_speed_switch().write(Rpm(75.0))?;
    drive
        .homing_acceleration()
        .write(RpsPerSecond(610.351_562_5))?;
    drive.homing_offset().write(Increments(1_000.0))?;
    drive.enable_operation(Instant::now() + Duration::from_secs(2))?;

    let home = drive.home(
        HomingMethod::METHOD17,
        Instant::now() + Duration::from_secs(10),
    )?;
    println!("homed (method 17, offset 1000 inc): position {home} inc");

    let window = drive.target_position_window().read_raw()?;
    for target in POSITIONS {
        let reached = drive.move_to(Move::to(target), Instant::now() + Duration::from_secs(10))?;
        let error = target - reached;
        println!("moved to {target:>8} inc: position {reached:>8} inc, error {error} inc (window {window})");
    }
    drive.disable(Instant::now() + Duration::from_secs(2))?;
    Ok(())
}

//! The typed motion API (issue 32) against the simulated Kinco over CANopen on an in-process
//! bus (and once over RS-232): homing onto the simulated switch with the home offset, profile position moves absolute
//! and relative, and each refusal and failure as its typed error — a target outside the
//! software limits, a homing method the description does not list, a move while not operation
//! enabled (nothing sent), a following error and a time out (the axis halted).

use std::time::{Duration, Instant};

use drivebus::canopen::can::in_process::InProcessEndpoint;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::control::motion_error::MotionError;
use drivebus::control::position::{Move, SoftLimits};
use drivebus::rs232::{LoopMode, StationId};
use drivesim::canopen::{InProcessNode, NodeConfig};
use drivesim::rs232::{InProcessLine, Rs232Server};
use drivesim::Simulator;
use kinco_fd::types::HomingMethod;
use kinco_fd::KincoFd;

type Drive = KincoFd<CanOpenLink<BlockingSdo<InProcessEndpoint>>>;

/// The simulated node, running until dropped, and its simulator (for the test's own hooks).
struct Running {
    sim: Simulator,
    _node: InProcessNode,
}

fn start() -> (Drive, Running) {
    let description = concat!(env!("CARGO_MANIFEST_DIR"), "/../../descriptions/kinco-fd");
    let sim = Simulator::load(description).unwrap();
    let config = NodeConfig {
        node: NodeId(1),
        heartbeat: None,
    };
    let (client, node) = InProcessNode::start(sim.clone(), config);
    let sdo = BlockingSdo::new(client).with_timeout(Duration::from_millis(500));
    let drive = KincoFd::canopen(sdo, NodeId::new(1).unwrap());
    (drive, Running { sim, _node: node })
}

fn soon(seconds: u64) -> Instant {
    Instant::now() + Duration::from_secs(seconds)
}

/// A quick profile (raw units: the simulated axis takes velocity units as position units per
/// second), then operation enabled; over any link.
macro_rules! quick_and_enabled {
    ($drive:expr) => {{
        $drive.profile_speed().write_raw(200_000).unwrap();
        $drive.profile_acceleration().write_raw(1_000_000).unwrap();
        $drive.profile_deceleration().write_raw(1_000_000).unwrap();
        $drive.homing_speed_switch().write_raw(100_000).unwrap();
        $drive.homing_acceleration().write_raw(1_000_000).unwrap();
        $drive.enable_operation(soon(2)).unwrap();
    }};
}

/// Operation enabled over CANopen, with the quick profile.
fn enabled() -> (Drive, Running) {
    let (mut drive, running) = start();
    quick_and_enabled!(drive);
    (drive, running)
}

#[test]
fn homes_then_moves_to_positions_absolute_and_relative() {
    let (mut drive, running) = enabled();
    running.sim.with(|d| d.place_home_switch(Some(-20_000)));
    drive.homing_offset().write_raw(500).unwrap();
    let home = drive.home(HomingMethod::METHOD17, soon(5)).unwrap();
    assert_eq!(home, -500, "home is minus the home offset");

    assert_eq!(drive.move_to(Move::to(50_000), soon(5)).unwrap(), 50_000);
    assert_eq!(drive.move_to(Move::by(-10_000), soon(5)).unwrap(), 40_000);
    let position = drive.position_actual().read_raw().unwrap();
    assert_eq!(position, 40_000);
    let status = drive.statusword().read_raw().unwrap();
    assert_eq!(
        status & 0x146F,
        0x0427,
        "operation enabled, target reached: {status:#06X}"
    );
}

#[test]
fn refusals_send_nothing() {
    let (mut drive, running) = enabled();
    drive.soft_positive_limit().write_raw(100_000).unwrap();
    drive.soft_negative_limit().write_raw(-100_000).unwrap();
    let error = drive.move_to(Move::to(100_001), soon(2)).unwrap_err();
    let limits = SoftLimits::between(-100_000, 100_000).unwrap();
    assert_eq!(
        error,
        MotionError::OutsideLimits {
            target: 100_001,
            limits
        }
    );
    let target = drive.target_position().read_raw().unwrap();
    assert_eq!(target, 0, "the target was not written");

    // A method the drive sent but the description does not list (36) is refused.
    drive.homing_method().write_raw(36).unwrap();
    let unlisted = drive.homing_method().read().unwrap();
    assert_eq!(
        drive.home(unlisted, soon(2)).unwrap_err(),
        MotionError::HomingMethodNotListed { method: 36 }
    );

    drive.disable(soon(2)).unwrap();
    let error = drive.move_to(Move::to(1_000), soon(2)).unwrap_err();
    assert!(
        matches!(error, MotionError::NotOperationEnabled { status: 0x0040 }),
        "{error:?}"
    );
    let mode = running.sim.with(|d| {
        let id = d.store().id("modes_of_operation").unwrap();
        d.store().int(id)
    });
    assert_eq!(mode, Some(0), "the mode was not written");
}

#[test]
fn a_following_error_and_a_time_out_halt_the_axis() {
    let (mut drive, running) = enabled();
    drive.max_following_error().write_raw(1_000).unwrap();
    running.sim.with(|d| d.block_load(true));
    let error = drive.move_to(Move::to(50_000), soon(5)).unwrap_err();
    assert!(
        matches!(error, MotionError::FollowingError { .. }),
        "{error:?}"
    );
    let controlword = drive.controlword().read_raw().unwrap();
    assert_ne!(controlword & 0x0100, 0, "halted: {controlword:#06X}");
    running.sim.with(|d| d.block_load(false));

    let (mut drive, _running) = enabled();
    drive.profile_speed().write_raw(1_000).unwrap();
    let error = drive
        .move_to(
            Move::to(50_000),
            Instant::now() + Duration::from_millis(300),
        )
        .unwrap_err();
    assert!(matches!(error, MotionError::Timeout { .. }), "{error:?}");
    let controlword = drive.controlword().read_raw().unwrap();
    assert_ne!(controlword & 0x0100, 0, "halted: {controlword:#06X}");
}

#[test]
fn homing_without_a_switch_is_a_homing_error() {
    let (mut drive, running) = enabled();
    running.sim.with(|d| d.place_home_switch(None));
    let error = drive.home(HomingMethod::METHOD17, soon(2)).unwrap_err();
    assert!(
        matches!(error, MotionError::HomingError { .. }),
        "{error:?}"
    );
}

/// The manual's homing and position sequences over the Kinco RS-232 protocol (sections 10.4 and
/// 11.x print them as telegrams): the same typed calls, through the simulator's RS-232 server.
#[test]
fn homes_and_moves_over_rs232() {
    let description = concat!(env!("CARGO_MANIFEST_DIR"), "/../../descriptions/kinco-fd");
    let sim = Simulator::load(description).unwrap();
    let server = Rs232Server::new(&sim, StationId(1), LoopMode::PointToPoint);
    let mut drive = KincoFd::rs232(InProcessLine::new(server), StationId(1));
    quick_and_enabled!(drive);
    assert_eq!(drive.home(HomingMethod::METHOD33, soon(5)).unwrap(), 0);
    assert_eq!(drive.move_to(Move::to(50_000), soon(5)).unwrap(), 50_000);
}

#[test]
fn runs_at_a_velocity_then_applies_a_torque() {
    let (mut drive, running) = enabled();
    let speed = drive.run_at_velocity(100_000, soon(5)).unwrap();
    assert_eq!(speed, 100_000, "target reached at the set velocity");
    assert_eq!(drive.modes_of_operation_display().read_raw().unwrap(), 3);
    drive.apply_torque(10, soon(5)).unwrap();
    assert_eq!(drive.modes_of_operation_display().read_raw().unwrap(), 4);
    // The simulated load settles at 1000 / 2 velocity units per torque unit.
    std::thread::sleep(Duration::from_millis(500));
    let speed = running.sim.with(|d| {
        let id = d.store().id("velocity_actual_value").unwrap();
        d.store().int(id).unwrap()
    });
    assert!(speed > 0, "the torque moves the load: {speed}");
}

#[test]
fn velocity_and_torque_are_refused_unless_operation_enabled() {
    let (mut drive, _running) = start();
    let refused = drive.run_at_velocity(1_000, soon(1)).unwrap_err();
    assert!(
        matches!(refused, MotionError::NotOperationEnabled { .. }),
        "{refused}"
    );
    let refused = drive.apply_torque(5, soon(1)).unwrap_err();
    assert!(
        matches!(refused, MotionError::NotOperationEnabled { .. }),
        "{refused}"
    );
    assert_eq!(drive.target_torque().read_raw().unwrap(), 0, "nothing sent");
}

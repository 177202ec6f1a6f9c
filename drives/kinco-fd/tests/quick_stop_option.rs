//! A quick stop seen through to the end the Kinco's quick stop option code gives (605Ah, manual
//! section 8.13 line 2128), against the simulated Kinco over CANopen on an in-process bus, through
//! the generated `quick_stop_by_option_code` (which reads 605Ah itself): with "stop by using
//! ramp, then switch off" (1) the driver waits, writing nothing, while the axis brakes in quick
//! stop active, and returns once the drive has taken transition 12 to switch on disabled; with
//! "stay in quick stop active" (5) it returns there; expecting the wrong end
//! (`driver::quick_stop_to`) is a typed error.

use std::time::{Duration, Instant};

use drivebus::canopen::can::in_process::InProcessEndpoint;
use drivebus::canopen::client::BlockingSdo;
use drivebus::canopen::{CanOpenLink, NodeId};
use drivebus::control::driver::{self, ControlError};
use drivebus::control::stop_option::QuickStopEnd;
use drivebus::control::State;
use drivesim::canopen::{InProcessNode, NodeConfig};
use drivesim::Simulator;
use kinco_fd::types::StopMode;
use kinco_fd::KincoFd;

type Drive = KincoFd<CanOpenLink<BlockingSdo<InProcessEndpoint>>>;

fn soon(seconds: u64) -> Instant {
    Instant::now() + Duration::from_secs(seconds)
}

/// The simulated Kinco with quick stop option `mode`, moving at 100 000 units/s in profile
/// position mode with a profile deceleration of 200 000 units/s² (0.5 s to stop on the slow
/// down ramp).
fn moving(mode: StopMode) -> (Drive, InProcessNode) {
    let description = concat!(env!("CARGO_MANIFEST_DIR"), "/../../descriptions/kinco-fd");
    let sim = Simulator::load(description).unwrap();
    let config = NodeConfig {
        node: NodeId(1),
        heartbeat: None,
    };
    let (client, node) = InProcessNode::start(sim, config);
    let sdo = BlockingSdo::new(client).with_timeout(Duration::from_millis(500));
    let mut drive = KincoFd::canopen(sdo, NodeId::new(1).unwrap());
    drive.quick_stop_mode().write(mode).unwrap();
    drive.profile_speed().write_raw(100_000).unwrap();
    drive.profile_acceleration().write_raw(1_000_000).unwrap();
    drive.profile_deceleration().write_raw(200_000).unwrap();
    drive
        .quick_stop_deceleration()
        .write_raw(10_000_000)
        .unwrap();
    drive.enable_operation(soon(2)).unwrap();
    drive.modes_of_operation().write_raw(1).unwrap();
    drive.target_position().write_raw(100_000_000).unwrap();
    drive.controlword().write_raw(0x1F).unwrap();
    drive.controlword().write_raw(0x0F).unwrap();
    std::thread::sleep(Duration::from_millis(300));
    assert_ne!(drive.velocity_actual_value().read_raw().unwrap(), 0);
    (drive, node)
}

/// The end the drive's own option code gives, read through the typed API.
fn end(drive: &mut Drive) -> QuickStopEnd {
    QuickStopEnd::of_code(drive.quick_stop_mode().read().unwrap().raw().into())
}

#[test]
fn a_ramp_then_off_quick_stop_returns_once_braked_and_switched_off() {
    let (mut drive, _node) = moving(StopMode::RAMP_THEN_OFF);
    let end = end(&mut drive);
    assert_eq!(end, QuickStopEnd::SwitchOnDisabled);
    let started = Instant::now();
    drive.quick_stop_by_option_code(soon(3)).unwrap();
    let braked = started.elapsed();
    assert!(
        braked >= Duration::from_millis(400),
        "returned before the 0.5 s ramp: {braked:?}"
    );
    assert_eq!(drive.cia402_state(), Ok(Some(State::SwitchOnDisabled)));
    assert_eq!(drive.velocity_actual_value().read_raw().unwrap(), 0);
}

#[test]
fn a_quick_stop_that_stays_ends_in_quick_stop_active_and_a_wrong_expectation_is_an_error() {
    let (mut drive, _node) = moving(StopMode::PROFILE_DECELERATION_STAY);
    let end = end(&mut drive);
    assert_eq!(end, QuickStopEnd::QuickStopActive);
    drive.quick_stop_by_option_code(soon(3)).unwrap();
    assert_eq!(drive.cia402_state(), Ok(Some(State::QuickStopActive)));

    // The drive switches off (code 0) where the caller expects it to stay.
    let (mut drive, _node) = moving(StopMode::WITHOUT_CONTROL);
    let expected = QuickStopEnd::QuickStopActive;
    let error = driver::quick_stop_to::<Drive, _>(drive.device(), expected, soon(3)).unwrap_err();
    assert!(
        matches!(
            error,
            ControlError::Stuck {
                state: Some("switch on disabled"),
                ..
            }
        ),
        "{error}"
    );
}

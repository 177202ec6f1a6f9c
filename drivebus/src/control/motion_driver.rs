//! The blocking shell of the motion planners: a profile position move, a homing run and a new
//! target in profile velocity or torque, each
//! refused before anything is sent when it cannot be made (not operation enabled, a target
//! outside the software limits, a homing method the description does not list), then driven by
//! polling the statusword until done, failed or the deadline. A following error, homing error or
//! time out halts the axis (controlword bit 8) before the error is returned, so it is never left
//! enabled heading for a stale target.

use std::thread;

use super::driver::{set_mode, Instant, POLL_INTERVAL};
use super::homing::HomingPlanner;
use super::mode_bits::{HOMING, PROFILE_POSITION, PROFILE_TORQUE, PROFILE_VELOCITY};
use super::motion_error::MotionError;
use super::motion_poll::{self, Poll};
use super::objects_on::{
    ControlOn, HomingOn, ModeOn, ProfilePositionOn, ProfileTorqueOn, ProfileVelocityOn,
};
use super::position::{Move, MovePlanner, SoftLimits};
use super::profile_target::{ProfileTarget, TargetPlanner};
use crate::device::Device;
use crate::link::Link;
use crate::parameter::{FromWire, OpenEnum};

/// Refuses unless the drive is operation enabled.
fn enabled<O, L>(device: &mut Device<L>) -> Result<(), MotionError>
where
    O: ControlOn<L::Protocol>,
    L: Link,
{
    motion_poll::check_enabled(device.read_raw::<O::Statusword>()?)
}

/// Moves to `request.target` in profile position mode (switching to it first) and returns the
/// position actual value once the drive reports target reached. `limits` are the software
/// position limits (607Dh) the generated handle read, if the drive has them; a relative target
/// is checked from the actual position.
pub fn move_to<O, L>(
    device: &mut Device<L>,
    request: Move,
    limits: Option<SoftLimits>,
    deadline: Instant,
) -> Result<i32, MotionError>
where
    O: ProfilePositionOn<L::Protocol>,
    L: Link,
{
    enabled::<O, L>(device)?;
    let actual = match (limits, request.relative) {
        (Some(_), true) => Some(device.read_raw::<O::PositionActual>()?),
        _ => None,
    };
    motion_poll::check_limits(request, limits, actual)?;
    let mode = O::Mode::from_raw(PROFILE_POSITION, FromWire(()));
    set_mode::<O, L>(device, mode, deadline)?;
    device.write_raw::<O::TargetPosition>(request.target)?;
    let mut planner = MovePlanner::new(request, device.read_raw::<O::Controlword>()?);
    let halt = planner.halt();
    run::<O, L>(device, deadline, halt, |status| {
        motion_poll::of_move(&mut planner, status)
    })?;
    Ok(device.read_raw::<O::PositionActual>()?)
}

/// Runs at `velocity` (60FFh, in the drive's velocity units) in profile velocity mode
/// (switching to it first) and returns the velocity actual value once the drive reports target
/// reached (bit 10) before `deadline`. Refused before anything is sent unless the drive is
/// operation enabled; a maximum slippage error or time out halts the axis and is returned. The
/// axis goes on running at the velocity: halt it, or call again with 0, to stop.
pub fn run_at_velocity<O, L>(
    device: &mut Device<L>,
    velocity: i32,
    deadline: Instant,
) -> Result<i32, MotionError>
where
    O: ProfileVelocityOn<L::Protocol>,
    L: Link,
{
    enter::<O, L>(device, PROFILE_VELOCITY, deadline)?;
    device.write_raw::<O::TargetVelocity>(velocity)?;
    target::<O, L>(device, ProfileTarget::Velocity, deadline)?;
    Ok(device.read_raw::<O::VelocityActual>()?)
}

/// Applies `torque` (6071h, in the drive's torque units) in profile torque mode (switching to
/// it first) and returns once the drive reports target reached (bit 10) before `deadline`.
/// Refused before anything is sent unless the drive is operation enabled; a time out halts the
/// axis and is returned.
pub fn apply_torque<O, L>(
    device: &mut Device<L>,
    torque: i16,
    deadline: Instant,
) -> Result<(), MotionError>
where
    O: ProfileTorqueOn<L::Protocol>,
    L: Link,
{
    enter::<O, L>(device, PROFILE_TORQUE, deadline)?;
    device.write_raw::<O::TargetTorque>(torque)?;
    target::<O, L>(device, ProfileTarget::Torque, deadline)
}

/// Refuses unless the drive is operation enabled, then switches to `mode`.
fn enter<O, L>(device: &mut Device<L>, mode: i8, deadline: Instant) -> Result<(), MotionError>
where
    O: ControlOn<L::Protocol> + ModeOn<L::Protocol>,
    L: Link,
{
    enabled::<O, L>(device)?;
    set_mode::<O, L>(device, O::Mode::from_raw(mode, FromWire(())), deadline)?;
    Ok(())
}

/// Drives a [`TargetPlanner`] until target reached.
fn target<O, L>(
    device: &mut Device<L>,
    target: ProfileTarget,
    deadline: Instant,
) -> Result<(), MotionError>
where
    O: ControlOn<L::Protocol>,
    L: Link,
{
    let mut planner = TargetPlanner::new(target);
    let halt = planner.halt();
    run::<O, L>(device, deadline, halt, |status| {
        motion_poll::of_target(&mut planner, target, status)
    })
}

/// Homes with `method` in homing mode (switching to it first), the speeds, acceleration and
/// offset as the drive holds them, and returns the position actual value once homing is
/// attained.
pub fn home<O, L>(
    device: &mut Device<L>,
    method: O::Method,
    deadline: Instant,
) -> Result<i32, MotionError>
where
    O: HomingOn<L::Protocol>,
    L: Link,
{
    motion_poll::check_method(method)?;
    enabled::<O, L>(device)?;
    let mode = O::Mode::from_raw(HOMING, FromWire(()));
    set_mode::<O, L>(device, mode, deadline)?;
    device.write::<O::HomingMethod>(method)?;
    let mut planner =
        HomingPlanner::new(device.read_raw::<O::Controlword>()?).with_quirks(O::QUIRKS);
    let halt = planner.halt();
    run::<O, L>(device, deadline, halt, |status| {
        motion_poll::of_homing(&mut planner, status)
    })?;
    Ok(device.read_raw::<O::PositionActual>()?)
}

/// A planner's answer to a statusword, as the poll loop acts on it.
/// Reads the statusword and acts on `next`'s answer until done or failed; a failure the drive
/// does not stop on by itself, or the deadline, writes `halt` first.
fn run<O, L>(
    device: &mut Device<L>,
    deadline: Instant,
    halt: u16,
    mut next: impl FnMut(u16) -> Poll,
) -> Result<(), MotionError>
where
    O: ControlOn<L::Protocol>,
    L: Link,
{
    loop {
        let status = device.read_raw::<O::Statusword>()?;
        match next(status) {
            Poll::Done => return Ok(()),
            Poll::Send(controlword) => {
                device.write_raw::<O::Controlword>(controlword)?;
                continue;
            }
            Poll::Fail(error) => {
                if error.is_halted() {
                    device.write_raw::<O::Controlword>(halt)?;
                }
                return Err(error);
            }
            Poll::Wait => {}
        }
        if Instant::now() >= deadline {
            device.write_raw::<O::Controlword>(halt)?;
            return Err(MotionError::Timeout { status });
        }
        thread::sleep(POLL_INTERVAL);
    }
}

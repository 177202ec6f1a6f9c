//! The async shell of the motion planners (features `async` and `std`): a profile position
//! move, a homing run and a new target in profile velocity or torque, awaited over an async
//! link. The refusals and each step are the blocking shell's ([`motion_poll`]); only the reads,
//! writes and waits differ. The whole procedure runs within its time limit on the application's
//! [`Timer`]; when it runs out, the axis is halted (controlword bit 8) before
//! [`MotionError::Timeout`] is returned, as the blocking shell does at its deadline.

use core::time::Duration;

use super::async_driver::set_mode;
use super::homing::HomingPlanner;
use super::mode_bits::{HOMING, PROFILE_POSITION, PROFILE_TORQUE, PROFILE_VELOCITY};
use super::motion_error::MotionError;
use super::motion_poll::{self, Poll};
use super::objects::{
    Cia402Modes, Cia402Objects, HomingObjects, ProfilePositionObjects, ProfileTorqueObjects,
    ProfileVelocityObjects,
};
use super::position::{Move, MovePlanner, SoftLimits};
use super::profile_target::{ProfileTarget, TargetPlanner};
use super::walk::POLL_INTERVAL;
use crate::asynch::{within, Async, AsyncLink, Timer};
use crate::device::Device;
use crate::parameter::{FromWire, OpenEnum, Readable, Writable};

/// Refuses unless the drive is operation enabled.
async fn enabled<O, L>(device: &mut Device<Async<L>>) -> Result<(), MotionError>
where
    O: Cia402Objects,
    L: AsyncLink,
    O::Statusword: Readable<L::Protocol>,
{
    motion_poll::check_enabled(device.read_raw::<O::Statusword>().await?)
}

/// Moves to `request.target` in profile position mode, as the blocking `move_to`, within
/// `limit`; returns the position actual value at target reached.
pub async fn move_to<O, L>(
    device: &mut Device<Async<L>>,
    request: Move,
    limits: Option<SoftLimits>,
    timer: &impl Timer,
    limit: Duration,
) -> Result<i32, MotionError>
where
    O: ProfilePositionObjects,
    L: AsyncLink,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::Statusword: Readable<L::Protocol>,
    O::ModesOfOperation: Writable<L::Protocol>,
    O::ModesOfOperationDisplay: Readable<L::Protocol>,
    O::TargetPosition: Writable<L::Protocol>,
    O::PositionActual: Readable<L::Protocol>,
{
    enabled::<O, L>(device).await?;
    let actual = match (limits, request.relative) {
        (Some(_), true) => Some(device.read_raw::<O::PositionActual>().await?),
        _ => None,
    };
    motion_poll::check_limits(request, limits, actual)?;
    let mut planner = None;
    let mut last = None;
    let procedure = async {
        let mode = O::Mode::from_raw(PROFILE_POSITION, FromWire(()));
        set_mode::<O, L>(device, mode, timer, limit).await?;
        device
            .write_raw::<O::TargetPosition>(request.target)
            .await?;
        let controlword = device.read_raw::<O::Controlword>().await?;
        let planner = planner.insert(MovePlanner::new(request, controlword));
        run::<O, L>(device, timer, planner.halt(), &mut last, |status| {
            motion_poll::of_move(planner, status)
        })
        .await?;
        Ok(device.read_raw::<O::PositionActual>().await?)
    };
    let outcome = within(timer, limit, procedure).await;
    let halt = planner.as_ref().map(MovePlanner::halt);
    timed_out::<O, L, _>(device, outcome, halt, last).await
}

/// Runs at `velocity` in profile velocity mode, as the blocking `run_at_velocity`, within
/// `limit`; returns the velocity actual value at target reached.
pub async fn run_at_velocity<O, L>(
    device: &mut Device<Async<L>>,
    velocity: i32,
    timer: &impl Timer,
    limit: Duration,
) -> Result<i32, MotionError>
where
    O: ProfileVelocityObjects,
    L: AsyncLink,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::Statusword: Readable<L::Protocol>,
    O::ModesOfOperation: Writable<L::Protocol>,
    O::ModesOfOperationDisplay: Readable<L::Protocol>,
    O::TargetVelocity: Writable<L::Protocol>,
    O::VelocityActual: Readable<L::Protocol>,
{
    enabled::<O, L>(device).await?;
    let mut last = None;
    let target = ProfileTarget::Velocity;
    let mut planner = TargetPlanner::new(target);
    let halt = planner.halt();
    let procedure = async {
        enter::<O, L>(device, PROFILE_VELOCITY, timer, limit).await?;
        device.write_raw::<O::TargetVelocity>(velocity).await?;
        run::<O, L>(device, timer, halt, &mut last, |status| {
            motion_poll::of_target(&mut planner, target, status)
        })
        .await?;
        Ok(device.read_raw::<O::VelocityActual>().await?)
    };
    let outcome = within(timer, limit, procedure).await;
    timed_out::<O, L, _>(device, outcome, Some(halt), last).await
}

/// Applies `torque` in profile torque mode, as the blocking `apply_torque`, within `limit`.
pub async fn apply_torque<O, L>(
    device: &mut Device<Async<L>>,
    torque: i16,
    timer: &impl Timer,
    limit: Duration,
) -> Result<(), MotionError>
where
    O: ProfileTorqueObjects,
    L: AsyncLink,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::Statusword: Readable<L::Protocol>,
    O::ModesOfOperation: Writable<L::Protocol>,
    O::ModesOfOperationDisplay: Readable<L::Protocol>,
    O::TargetTorque: Writable<L::Protocol>,
{
    enabled::<O, L>(device).await?;
    let mut last = None;
    let target = ProfileTarget::Torque;
    let mut planner = TargetPlanner::new(target);
    let halt = planner.halt();
    let procedure = async {
        enter::<O, L>(device, PROFILE_TORQUE, timer, limit).await?;
        device.write_raw::<O::TargetTorque>(torque).await?;
        run::<O, L>(device, timer, halt, &mut last, |status| {
            motion_poll::of_target(&mut planner, target, status)
        })
        .await
    };
    let outcome = within(timer, limit, procedure).await;
    timed_out::<O, L, _>(device, outcome, Some(halt), last).await
}

/// Homes with `method`, as the blocking `home`, within `limit`; returns the position actual
/// value once homing is attained.
pub async fn home<O, L>(
    device: &mut Device<Async<L>>,
    method: O::Method,
    timer: &impl Timer,
    limit: Duration,
) -> Result<i32, MotionError>
where
    O: HomingObjects + ProfilePositionObjects,
    L: AsyncLink,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::Statusword: Readable<L::Protocol>,
    O::ModesOfOperation: Writable<L::Protocol>,
    O::ModesOfOperationDisplay: Readable<L::Protocol>,
    O::HomingMethod: Writable<L::Protocol>,
    O::PositionActual: Readable<L::Protocol>,
{
    motion_poll::check_method(method)?;
    enabled::<O, L>(device).await?;
    let mut planner = None;
    let mut last = None;
    let procedure = async {
        enter::<O, L>(device, HOMING, timer, limit).await?;
        device.write::<O::HomingMethod>(method).await?;
        let controlword = device.read_raw::<O::Controlword>().await?;
        let planner = planner.insert(HomingPlanner::new(controlword).with_quirks(O::QUIRKS));
        run::<O, L>(device, timer, planner.halt(), &mut last, |status| {
            motion_poll::of_homing(planner, status)
        })
        .await?;
        Ok(device.read_raw::<O::PositionActual>().await?)
    };
    let outcome = within(timer, limit, procedure).await;
    let halt = planner.as_ref().map(HomingPlanner::halt);
    timed_out::<O, L, _>(device, outcome, halt, last).await
}

/// Requests `mode` and waits for its display.
async fn enter<O, L>(
    device: &mut Device<Async<L>>,
    mode: i8,
    timer: &impl Timer,
    limit: Duration,
) -> Result<(), MotionError>
where
    O: Cia402Modes,
    L: AsyncLink,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::ModesOfOperation: Writable<L::Protocol>,
    O::ModesOfOperationDisplay: Readable<L::Protocol>,
{
    let mode = O::Mode::from_raw(mode, FromWire(()));
    Ok(set_mode::<O, L>(device, mode, timer, limit).await?)
}

/// Reads the statusword (kept in `last`) and acts on `next`'s answer until done or failed; a
/// failure the drive does not stop on by itself writes `halt` first.
async fn run<O, L>(
    device: &mut Device<Async<L>>,
    timer: &impl Timer,
    halt: u16,
    last: &mut Option<u16>,
    mut next: impl FnMut(u16) -> Poll,
) -> Result<(), MotionError>
where
    O: Cia402Objects,
    L: AsyncLink,
    O::Controlword: Writable<L::Protocol>,
    O::Statusword: Readable<L::Protocol>,
{
    loop {
        let status = device.read_raw::<O::Statusword>().await?;
        *last = Some(status);
        match next(status) {
            Poll::Done => return Ok(()),
            Poll::Send(controlword) => {
                device.write_raw::<O::Controlword>(controlword).await?;
                continue;
            }
            Poll::Fail(error) => {
                if error.is_halted() {
                    device.write_raw::<O::Controlword>(halt).await?;
                }
                return Err(error);
            }
            Poll::Wait => {}
        }
        timer.sleep(POLL_INTERVAL).await;
    }
}

/// The outcome of a procedure run within its limit: when the time ran out, the axis is halted
/// (once the planner had started it) and the error is a time out with the last statusword.
async fn timed_out<O, L, T>(
    device: &mut Device<Async<L>>,
    outcome: Result<Result<T, MotionError>, crate::asynch::Elapsed>,
    halt: Option<u16>,
    last: Option<u16>,
) -> Result<T, MotionError>
where
    O: Cia402Objects,
    L: AsyncLink,
    O::Controlword: Writable<L::Protocol>,
{
    match outcome {
        Ok(done) => done,
        Err(_) => {
            if let Some(halt) = halt {
                device.write_raw::<O::Controlword>(halt).await?;
            }
            Err(MotionError::Timeout {
                status: last.unwrap_or(0),
            })
        }
    }
}

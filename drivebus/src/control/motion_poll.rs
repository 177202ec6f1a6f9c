//! What a motion shell decides, without I/O: the refusals made before anything is sent and,
//! after each statusword read, what the planner asks for. The blocking shell (`motion_driver`)
//! and the async one (`async_motion_driver`) both run these, so they differ only in how they
//! read, write and wait.

use super::homing::{HomingPlanner, HomingStep};
use super::motion_error::MotionError;
use super::position::{operation_enabled, Move, MovePlanner, MoveStep, SoftLimits};
use super::profile_target::{ProfileTarget, TargetPlanner};
use crate::parameter::OpenEnum;

/// What to do after a statusword read.
#[derive(Debug, Clone, PartialEq)]
pub enum Poll {
    /// Write this controlword, then read again at once.
    Send(u16),
    /// Wait one poll interval, then read again.
    Wait,
    /// The procedure is done.
    Done,
    /// The procedure failed: write the halt first where [`MotionError::is_halted`] says so.
    Fail(MotionError),
}

/// Refuses unless `status` shows operation enabled.
pub fn check_enabled(status: u16) -> Result<(), MotionError> {
    if operation_enabled(status) {
        Ok(())
    } else {
        Err(MotionError::NotOperationEnabled { status })
    }
}

/// Refuses a move whose end lies outside `limits`; `actual` is the position actual value, read
/// only for a relative move (`None` otherwise).
pub fn check_limits(
    request: Move,
    limits: Option<SoftLimits>,
    actual: Option<i32>,
) -> Result<(), MotionError> {
    let Some(limits) = limits else {
        return Ok(());
    };
    let end = match (request.relative, actual) {
        (true, Some(actual)) => i64::from(actual) + i64::from(request.target),
        _ => i64::from(request.target),
    };
    if limits.allow(end) {
        Ok(())
    } else {
        Err(MotionError::OutsideLimits {
            target: end,
            limits,
        })
    }
}

/// Refuses a homing method the description does not list.
pub fn check_method<M: OpenEnum<Raw = i8>>(method: M) -> Result<(), MotionError> {
    match method.name() {
        Some(_) => Ok(()),
        None => Err(MotionError::HomingMethodNotListed {
            method: method.raw(),
        }),
    }
}

/// The step of a profile position move after reading `status`.
pub fn of_move(planner: &mut MovePlanner, status: u16) -> Poll {
    match planner.next(status) {
        MoveStep::Send(controlword) => Poll::Send(controlword),
        MoveStep::Wait => Poll::Wait,
        MoveStep::Done => Poll::Done,
        MoveStep::Failed(failure) => Poll::Fail(MotionError::of_move(failure, status)),
    }
}

/// The step of a new profile velocity or torque target after reading `status`.
pub fn of_target(planner: &mut TargetPlanner, target: ProfileTarget, status: u16) -> Poll {
    match planner.next(status) {
        MoveStep::Send(controlword) => Poll::Send(controlword),
        MoveStep::Wait => Poll::Wait,
        MoveStep::Done => Poll::Done,
        MoveStep::Failed(failure) => Poll::Fail(MotionError::of_target(target, failure, status)),
    }
}

/// The step of a homing run after reading `status`.
pub fn of_homing(planner: &mut HomingPlanner, status: u16) -> Poll {
    match planner.next(status) {
        HomingStep::Send(controlword) => Poll::Send(controlword),
        HomingStep::Wait => Poll::Wait,
        HomingStep::Done => Poll::Done,
        HomingStep::Failed(failure) => Poll::Fail(MotionError::of_homing(failure, status)),
    }
}

//! Every way a profile position move or a homing run fails, as one typed error: refused before
//! anything is sent, or stopped while it ran.

use core::fmt;

use super::driver::ControlError;
use super::homing::HomingFailure;
use super::position::{MoveFailure, SoftLimits};
use super::profile_target::{is_slippage, ProfileTarget};
use crate::error::Error;

/// A failed move or homing run.
#[derive(Debug, Clone, PartialEq)]
pub enum MotionError {
    /// Refused before sending: the drive is not in operation enabled.
    NotOperationEnabled {
        /// The statusword read.
        status: u16,
    },
    /// Refused before sending: the target lies outside the software position limits (607Dh).
    OutsideLimits {
        /// The absolute position the move would end on.
        target: i64,
        /// The limits in force.
        limits: SoftLimits,
    },
    /// Refused before sending: the homing method is not one the description lists.
    HomingMethodNotListed {
        /// The method's raw value.
        method: i8,
    },
    /// The following error exceeded its window (statusword bit 13); the move was halted.
    FollowingError {
        /// The statusword that reported it.
        status: u16,
    },
    /// The drive reported a maximum slippage error in profile velocity (statusword bit 13);
    /// the axis was halted.
    MaxSlippage {
        /// The statusword that reported it.
        status: u16,
    },
    /// The drive reported a homing error (statusword bit 13); homing was halted.
    HomingError {
        /// The statusword that reported it.
        status: u16,
    },
    /// The drive faulted during the move (statusword bit 3).
    Fault {
        /// The statusword that reported it.
        status: u16,
    },
    /// The drive left operation enabled during the move without a fault (quick stop, disable).
    LeftOperationEnabled {
        /// The statusword that reported it.
        status: u16,
    },
    /// The target was not reached before the deadline; the move was halted.
    Timeout {
        /// The statusword read last.
        status: u16,
    },
    /// Changing the mode of operation failed.
    Mode(ControlError),
    /// A read or write failed.
    Bus(Error),
}

impl MotionError {
    /// The error of a failed move, reported by `status`.
    pub fn of_move(failure: MoveFailure, status: u16) -> Self {
        match failure {
            MoveFailure::Fault => MotionError::Fault { status },
            MoveFailure::LeftOperationEnabled => MotionError::LeftOperationEnabled { status },
            MoveFailure::FollowingError => MotionError::FollowingError { status },
        }
    }

    /// Whether the axis is halted on this error: the drive goes on by itself after a following
    /// or homing error, so the master halts it; a fault or a state change stopped it already.
    pub const fn is_halted(&self) -> bool {
        matches!(
            self,
            MotionError::FollowingError { .. }
                | MotionError::MaxSlippage { .. }
                | MotionError::HomingError { .. }
                | MotionError::Timeout { .. }
        )
    }

    /// The error of a failed change of target in profile velocity or torque.
    pub fn of_target(target: ProfileTarget, failure: MoveFailure, status: u16) -> Self {
        if is_slippage(target, failure) {
            MotionError::MaxSlippage { status }
        } else {
            Self::of_move(failure, status)
        }
    }

    /// The error of a failed homing run, reported by `status`.
    pub fn of_homing(failure: HomingFailure, status: u16) -> Self {
        match failure {
            HomingFailure::Fault => MotionError::Fault { status },
            HomingFailure::LeftOperationEnabled => MotionError::LeftOperationEnabled { status },
            HomingFailure::HomingError => MotionError::HomingError { status },
        }
    }
}

impl From<Error> for MotionError {
    fn from(error: Error) -> Self {
        MotionError::Bus(error)
    }
}

impl From<ControlError> for MotionError {
    fn from(error: ControlError) -> Self {
        MotionError::Mode(error)
    }
}

impl fmt::Display for MotionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MotionError::NotOperationEnabled { status } => write!(
                f,
                "the drive is not operation enabled (status {status:#06x}); nothing was sent"
            ),
            MotionError::OutsideLimits { target, limits } => write!(
                f,
                "target {target} lies outside the software position limits {}..={}; nothing was sent",
                limits.min, limits.max
            ),
            MotionError::HomingMethodNotListed { method } => write!(
                f,
                "homing method {method} is not one the drive lists; nothing was sent"
            ),
            MotionError::FollowingError { status } => write!(
                f,
                "following error (status {status:#06x}); the move was halted"
            ),
            MotionError::MaxSlippage { status } => write!(
                f,
                "maximum slippage error (status {status:#06x}); the axis was halted"
            ),
            MotionError::HomingError { status } => {
                write!(f, "homing error (status {status:#06x}); homing was halted")
            }
            MotionError::Fault { status } => {
                write!(f, "the drive faulted during the move (status {status:#06x})")
            }
            MotionError::LeftOperationEnabled { status } => write!(
                f,
                "the drive left operation enabled during the move (status {status:#06x})"
            ),
            MotionError::Timeout { status } => write!(
                f,
                "not done before the deadline (status {status:#06x}); the move was halted"
            ),
            MotionError::Mode(e) => write!(f, "changing the mode of operation: {e}"),
            MotionError::Bus(e) => write!(f, "motion: {e}"),
        }
    }
}

impl std::error::Error for MotionError {}

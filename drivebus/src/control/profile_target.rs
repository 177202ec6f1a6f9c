//! Profile velocity (CiA 402 mode 3) and profile torque (mode 4) as one pure planner: the
//! caller writes the mode and the target (60FFh or 6071h) first, then feeds the planner each
//! statusword it reads. It clears halt (controlword enable operation, bit 8 clear), then waits
//! for target reached (bit 10: at the target velocity within the velocity window 606Dh, or at
//! the target torque, CiA 402-2), failing on a fault, a drive that leaves operation enabled or,
//! in profile velocity, a maximum slippage error (bit 13).
//!
//! Bit 10 may still show the previous target when the first statusword is read, so the planner
//! takes target reached only from a statusword read after its enable command was written.

use super::cia402::command::ENABLE_OPERATION;
use super::cia402::HALT_BIT;
use super::mode_bits::{MAX_SLIPPAGE, PROFILE_TORQUE, PROFILE_VELOCITY, TARGET_REACHED};
use super::position::{failure, MoveFailure, MoveStep};

/// Which profile mode a target is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileTarget {
    /// Profile velocity (3): the target velocity 60FFh.
    Velocity,
    /// Profile torque (4): the target torque 6071h.
    Torque,
}

impl ProfileTarget {
    /// The mode's number in 6060h.
    pub const fn mode(self) -> i8 {
        match self {
            ProfileTarget::Velocity => PROFILE_VELOCITY,
            ProfileTarget::Torque => PROFILE_TORQUE,
        }
    }

    /// The mode's error bit: maximum slippage in profile velocity, none in profile torque.
    const fn error_bit(self) -> u16 {
        match self {
            ProfileTarget::Velocity => MAX_SLIPPAGE,
            ProfileTarget::Torque => 0,
        }
    }
}

/// The planner of one change of target.
#[derive(Debug, Clone)]
pub struct TargetPlanner {
    target: ProfileTarget,
    enabled: bool,
}

impl TargetPlanner {
    /// A planner for a new target in `target`'s mode.
    pub const fn new(target: ProfileTarget) -> Self {
        Self {
            target,
            enabled: false,
        }
    }

    /// The halt the caller writes when it abandons the change (a time out or an error).
    pub const fn halt(&self) -> u16 {
        ENABLE_OPERATION | HALT_BIT
    }

    /// The next step, given the statusword just read. [`MoveFailure::FollowingError`] stands
    /// for the maximum slippage error in profile velocity.
    pub fn next(&mut self, statusword: u16) -> MoveStep {
        if let Some(failure) = failure(statusword, self.target.error_bit()) {
            return MoveStep::Failed(failure);
        }
        if !self.enabled {
            self.enabled = true;
            return MoveStep::Send(ENABLE_OPERATION);
        }
        if statusword & TARGET_REACHED != 0 {
            MoveStep::Done
        } else {
            MoveStep::Wait
        }
    }
}

/// Whether `failure` is the maximum slippage error of profile velocity.
pub const fn is_slippage(target: ProfileTarget, failure: MoveFailure) -> bool {
    matches!(
        (target, failure),
        (ProfileTarget::Velocity, MoveFailure::FollowingError)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const ENABLED: u16 = 0x0237;

    #[test]
    fn halt_is_cleared_then_target_reached_ends_it() {
        let mut planner = TargetPlanner::new(ProfileTarget::Velocity);
        assert_eq!(
            planner.next(ENABLED | TARGET_REACHED),
            MoveStep::Send(0x0F),
            "an old target reached is not taken"
        );
        assert_eq!(planner.next(ENABLED), MoveStep::Wait);
        assert_eq!(planner.next(ENABLED | TARGET_REACHED), MoveStep::Done);
        assert_eq!(planner.halt(), 0x010F);
        assert_eq!(ProfileTarget::Torque.mode(), 4);
    }

    #[test]
    fn slippage_faults_and_leaving_enabled_fail() {
        let mut velocity = TargetPlanner::new(ProfileTarget::Velocity);
        let slipped = velocity.next(ENABLED | MAX_SLIPPAGE);
        assert_eq!(slipped, MoveStep::Failed(MoveFailure::FollowingError));
        assert!(is_slippage(
            ProfileTarget::Velocity,
            MoveFailure::FollowingError
        ));
        let mut torque = TargetPlanner::new(ProfileTarget::Torque);
        assert_eq!(
            torque.next(ENABLED | MAX_SLIPPAGE),
            MoveStep::Send(0x0F),
            "bit 13 is reserved in profile torque"
        );
        assert_eq!(torque.next(0x0218), MoveStep::Failed(MoveFailure::Fault));
        assert_eq!(
            torque.next(0x0233),
            MoveStep::Failed(MoveFailure::LeftOperationEnabled)
        );
    }
}

//! Homing (CiA 402 mode 6) as a pure planner: a rising edge of controlword bit 4 starts it, the
//! drive reports homing attained (statusword bit 12) with target reached (bit 10), or a homing
//! error (bit 13). The caller writes the method (6098h), the speeds, acceleration and offset and
//! the mode first. The Kinco manual's sequence is 0x0F→0x1F, then 0xC037 "home found"
//! (`003_8cc8f7f4f05b8633.txt` lines 2490-2498, 3254-3260).

use super::cia402::command::ENABLE_OPERATION;
use super::mode_bits::{HOMING_ATTAINED, HOMING_ERROR, NEW_SET_POINT, TARGET_REACHED};
use super::position::{failure, MoveFailure};

/// Why homing failed, seen in the statusword.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HomingFailure {
    /// Statusword bit 3: the drive faulted.
    Fault,
    /// The drive left operation enabled (quick stop, disable) without a fault.
    LeftOperationEnabled,
    /// Statusword bit 13 in homing mode: the drive reports a homing error.
    HomingError,
}

/// What to do next.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HomingStep {
    /// Write this controlword.
    Send(u16),
    /// Read the statusword again.
    Wait,
    /// Homing attained; bit 4 is clear again.
    Done,
    /// Homing failed.
    Failed(HomingFailure),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Bit 4 is still set from an earlier command: clear it so the start is an edge.
    Clear,
    Start,
    AwaitAttained,
    Release,
}

/// The planner of one homing run.
#[derive(Debug, Clone)]
pub struct HomingPlanner {
    phase: Phase,
}

impl HomingPlanner {
    /// A homing run, given the controlword in force.
    pub const fn new(controlword: u16) -> Self {
        let phase = if controlword & NEW_SET_POINT != 0 {
            Phase::Clear
        } else {
            Phase::Start
        };
        Self { phase }
    }

    /// The halt the caller writes when it abandons homing (a time out): bit 8, bit 4 clear.
    pub const fn halt(&self) -> u16 {
        ENABLE_OPERATION | super::cia402::HALT_BIT
    }

    /// The next step, given the statusword just read.
    pub fn next(&mut self, statusword: u16) -> HomingStep {
        match failure(statusword, HOMING_ERROR) {
            Some(MoveFailure::Fault) => return HomingStep::Failed(HomingFailure::Fault),
            Some(MoveFailure::LeftOperationEnabled) => {
                return HomingStep::Failed(HomingFailure::LeftOperationEnabled)
            }
            // Bit 13 before the start is an earlier run's error, which the start clears.
            Some(MoveFailure::FollowingError) if self.phase == Phase::AwaitAttained => {
                return HomingStep::Failed(HomingFailure::HomingError)
            }
            _ => {}
        }
        let attained = statusword & (HOMING_ATTAINED | TARGET_REACHED);
        match self.phase {
            Phase::Clear => {
                self.phase = Phase::Start;
                HomingStep::Send(ENABLE_OPERATION)
            }
            Phase::Start => {
                self.phase = Phase::AwaitAttained;
                HomingStep::Send(ENABLE_OPERATION | NEW_SET_POINT)
            }
            Phase::AwaitAttained if attained == HOMING_ATTAINED | TARGET_REACHED => {
                self.phase = Phase::Release;
                HomingStep::Send(ENABLE_OPERATION)
            }
            Phase::AwaitAttained => HomingStep::Wait,
            Phase::Release => HomingStep::Done,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ENABLED: u16 = 0x0037;

    #[test]
    fn the_start_is_the_kinco_manuals_0f_to_1f_and_0xc037_is_home_found() {
        let mut planner = HomingPlanner::new(0x000F);
        assert_eq!(planner.next(ENABLED), HomingStep::Send(0x1F));
        assert_eq!(planner.next(ENABLED), HomingStep::Wait);
        // 0xC037: bits 14 and 15 are Kinco's own; no attained bit yet.
        assert_eq!(planner.next(0xC037), HomingStep::Wait);
        let attained = ENABLED | HOMING_ATTAINED | TARGET_REACHED;
        assert_eq!(planner.next(attained), HomingStep::Send(0x0F));
        assert_eq!(planner.next(attained), HomingStep::Done);
    }

    #[test]
    fn an_earlier_error_is_cleared_by_the_start_a_new_one_fails() {
        let mut planner = HomingPlanner::new(0x001F);
        assert_eq!(planner.next(ENABLED | HOMING_ERROR), HomingStep::Send(0x0F));
        assert_eq!(planner.next(ENABLED | HOMING_ERROR), HomingStep::Send(0x1F));
        assert_eq!(
            planner.next(ENABLED | HOMING_ERROR),
            HomingStep::Failed(HomingFailure::HomingError)
        );
        assert_eq!(
            HomingPlanner::new(0x0F).next(0x0008),
            HomingStep::Failed(HomingFailure::Fault)
        );
    }
}

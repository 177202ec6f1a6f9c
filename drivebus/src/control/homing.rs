//! Homing (CiA 402 mode 6) as a pure planner: a rising edge of controlword bit 4 starts it, the
//! drive reports homing attained (statusword bit 12) with target reached (bit 10), or a homing
//! error (bit 13). The caller writes the method (6098h), the speeds, acceleration and offset and
//! the mode first. The Kinco manual's sequence is 0x0F→0x1F, then 0xC037 "home found"
//! (`003_8cc8f7f4f05b8633.txt` lines 2490-2498, 3254-3260): bit 15, Kinco's `Reference_found`
//! (line 1936), with bits 12 and 10 clear. A drive declaring the quirk
//! [`HomingAttainedBit15`](super::quirks::Quirk::HomingAttainedBit15) is taken as homed when bit
//! 15 rises after the start: seen clear, then set. A bit 15 left set by an earlier homing is not
//! taken (the manual does not say whether the drive clears it at a new start); if the drive
//! never shows it clear, the run ends as CiA 402 says (bits 12 and 10) or by its time out, never
//! by a stale bit.

use super::cia402::command::ENABLE_OPERATION;
use super::mode_bits::{HOMING_ATTAINED, HOMING_ERROR, NEW_SET_POINT, TARGET_REACHED};
use super::position::{failure, MoveFailure};
use super::quirks::Quirks;

/// Statusword bit 15 (Kinco: `Reference_found`), homing attained on a drive with the quirk
/// [`HomingAttainedBit15`](super::quirks::Quirk::HomingAttainedBit15).
pub const REFERENCE_FOUND: u16 = 1 << 15;

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
    /// Bit 15 counts as homing attained (the quirk).
    bit_15: bool,
    /// Bit 15 was seen clear since the start.
    bit_15_cleared: bool,
}

impl HomingPlanner {
    /// A homing run, given the controlword in force.
    pub const fn new(controlword: u16) -> Self {
        let phase = if controlword & NEW_SET_POINT != 0 {
            Phase::Clear
        } else {
            Phase::Start
        };
        Self {
            phase,
            bit_15: false,
            bit_15_cleared: false,
        }
    }

    /// The same run on a drive with `quirks` (homing attained by bit 15 where declared).
    pub const fn with_quirks(mut self, quirks: Quirks) -> Self {
        self.bit_15 = quirks.homing_attained_bit_15;
        self
    }

    /// Whether `statusword` says homing attained: bits 12 and 10 (CiA 402), or with the quirk
    /// bit 15 set after it was seen clear since the start.
    fn attained(&mut self, statusword: u16) -> bool {
        let both = HOMING_ATTAINED | TARGET_REACHED;
        if !self.bit_15 {
            return statusword & both == both;
        }
        let reference = statusword & REFERENCE_FOUND != 0;
        self.bit_15_cleared |= !reference;
        statusword & both == both || (reference && self.bit_15_cleared)
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
        let attained = self.phase == Phase::AwaitAttained && self.attained(statusword);
        match self.phase {
            Phase::Clear => {
                self.phase = Phase::Start;
                HomingStep::Send(ENABLE_OPERATION)
            }
            Phase::Start => {
                self.phase = Phase::AwaitAttained;
                HomingStep::Send(ENABLE_OPERATION | NEW_SET_POINT)
            }
            Phase::AwaitAttained if attained => {
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
    fn with_the_bit_15_quirk_0xc037_after_a_clear_bit_15_is_home_found() {
        let quirks = Quirks::STANDARD.with(super::super::quirks::Quirk::HomingAttainedBit15);
        let mut planner = HomingPlanner::new(0x000F).with_quirks(quirks);
        assert_eq!(planner.next(0xC037), HomingStep::Send(0x1F));
        // Still set from an earlier run: not taken.
        assert_eq!(planner.next(0xC037), HomingStep::Wait);
        assert_eq!(planner.next(0x4037), HomingStep::Wait, "searching");
        assert_eq!(planner.next(0xC037), HomingStep::Send(0x0F));
        assert_eq!(planner.next(0xC037), HomingStep::Done);

        // As CiA 402 says, too.
        let mut planner = HomingPlanner::new(0x000F).with_quirks(quirks);
        assert_eq!(planner.next(ENABLED), HomingStep::Send(0x1F));
        let attained = ENABLED | HOMING_ATTAINED | TARGET_REACHED;
        assert_eq!(
            planner.next(attained | REFERENCE_FOUND),
            HomingStep::Send(0x0F)
        );
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

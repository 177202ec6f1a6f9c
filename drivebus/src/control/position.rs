//! A profile position move (CiA 402 mode 1) as a pure planner: the set-point handshake of
//! controlword bit 4 and statusword bit 12, then target reached (bit 10), failing on a following
//! error (bit 13), a fault or a drive that leaves operation enabled. The caller writes the
//! target position (607Ah) and the mode first, then feeds the planner each statusword it reads
//! and writes the controlwords it answers; the Kinco manual's own sequence is 0x2F→0x3F
//! (absolute, change immediately) or 0x4F→0x5F (relative) (`003_8cc8f7f4f05b8633.txt` lines
//! 2500-2513, 3266-3273).

use super::cia402::command::ENABLE_OPERATION;
use super::mode_bits::{
    CHANGE_IMMEDIATELY, FOLLOWING_ERROR, NEW_SET_POINT, RELATIVE, SET_POINT_ACKNOWLEDGE,
    TARGET_REACHED,
};

/// A move to request.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Move {
    /// The target position (607Ah), in position units.
    pub target: i32,
    /// Relative to the preceding target (controlword bit 6) instead of absolute.
    pub relative: bool,
    /// Replace a move in progress at once (bit 5) instead of following it (single set-point).
    pub change_immediately: bool,
}

impl Move {
    /// An absolute move to `target` that replaces a move in progress.
    pub const fn to(target: i32) -> Self {
        Self {
            target,
            relative: false,
            change_immediately: true,
        }
    }

    /// A move by `distance` from the preceding target, replacing a move in progress.
    pub const fn by(distance: i32) -> Self {
        Self {
            target: distance,
            relative: true,
            change_immediately: true,
        }
    }

    /// The controlword bits 5 and 6 of this move.
    const fn flags(&self) -> u16 {
        let relative = if self.relative { RELATIVE } else { 0 };
        let immediately = if self.change_immediately {
            CHANGE_IMMEDIATELY
        } else {
            0
        };
        relative | immediately
    }
}

/// The software position limits (607Dh), lower and upper whatever sub-index holds which (the
/// Kinco manual puts the positive limit at sub 1, CiA 402 the minimum: `kinco-fd` ERRATA #49).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SoftLimits {
    /// The lowest position allowed.
    pub min: i32,
    /// The highest position allowed.
    pub max: i32,
}

impl SoftLimits {
    /// The limits two sub-indices hold, in either order; `None` when both are 0, which drives
    /// use for "no software limit".
    pub fn between(a: i32, b: i32) -> Option<Self> {
        (a != 0 || b != 0).then(|| Self {
            min: a.min(b),
            max: a.max(b),
        })
    }

    /// Whether `position` lies within the limits.
    pub const fn allow(&self, position: i64) -> bool {
        self.min as i64 <= position && position <= self.max as i64
    }
}

/// Why a move in progress failed, seen in the statusword.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MoveFailure {
    /// Statusword bit 3: the drive faulted.
    Fault,
    /// The drive left operation enabled (quick stop, disable) without a fault.
    LeftOperationEnabled,
    /// Statusword bit 13 in profile position mode: the following error exceeded its window.
    FollowingError,
}

/// What to do next.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MoveStep {
    /// Write this controlword.
    Send(u16),
    /// Read the statusword again.
    Wait,
    /// The drive stands on the target.
    Done,
    /// The move failed.
    Failed(MoveFailure),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Bit 4 is still set from an earlier command: clear it so the next set is an edge.
    Clear,
    Start,
    AwaitAcknowledge,
    AwaitReached,
}

/// The statusword bits of the CiA 402 state (0-3, 5, 6) and their value in operation enabled.
const STATE_MASK: u16 = 0x006F;
const OPERATION_ENABLED: u16 = 0x0027;
const FAULT_BIT: u16 = 1 << 3;

/// Whether the statusword shows operation enabled.
pub const fn operation_enabled(statusword: u16) -> bool {
    statusword & STATE_MASK == OPERATION_ENABLED
}

/// What a statusword says against going on, whatever the phase.
pub(super) fn failure(statusword: u16, error_bit: u16) -> Option<MoveFailure> {
    if statusword & FAULT_BIT != 0 {
        Some(MoveFailure::Fault)
    } else if !operation_enabled(statusword) {
        Some(MoveFailure::LeftOperationEnabled)
    } else if statusword & error_bit != 0 {
        Some(MoveFailure::FollowingError)
    } else {
        None
    }
}

/// The planner of one move.
#[derive(Debug, Clone)]
pub struct MovePlanner {
    request: Move,
    phase: Phase,
}

impl MovePlanner {
    /// A move, given the controlword in force (to know whether bit 4 must fall first).
    pub const fn new(request: Move, controlword: u16) -> Self {
        let phase = if controlword & NEW_SET_POINT != 0 {
            Phase::Clear
        } else {
            Phase::Start
        };
        Self { request, phase }
    }

    /// The controlword of every step: enable operation, halt clear, this move's bits 5 and 6.
    const fn base(&self) -> u16 {
        ENABLE_OPERATION | self.request.flags()
    }

    /// The halt the caller writes when it abandons the move (a time out): bit 8, bit 4 clear.
    pub const fn halt(&self) -> u16 {
        self.base() | super::cia402::HALT_BIT
    }

    /// The next step, given the statusword just read.
    pub fn next(&mut self, statusword: u16) -> MoveStep {
        if let Some(failure) = failure(statusword, FOLLOWING_ERROR) {
            return MoveStep::Failed(failure);
        }
        let acknowledged = statusword & SET_POINT_ACKNOWLEDGE != 0;
        match self.phase {
            Phase::Clear => {
                self.phase = Phase::Start;
                MoveStep::Send(self.base())
            }
            Phase::Start => {
                self.phase = Phase::AwaitAcknowledge;
                MoveStep::Send(self.base() | NEW_SET_POINT)
            }
            Phase::AwaitAcknowledge if acknowledged => {
                self.phase = Phase::AwaitReached;
                // The set-point is taken: bit 4 falls, so the drive can take the next one.
                MoveStep::Send(self.base())
            }
            Phase::AwaitAcknowledge => MoveStep::Wait,
            Phase::AwaitReached if !acknowledged && statusword & TARGET_REACHED != 0 => {
                MoveStep::Done
            }
            Phase::AwaitReached => MoveStep::Wait,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ENABLED: u16 = 0x0037;

    #[test]
    fn the_handshake_is_the_kinco_manuals_sequence() {
        let mut absolute = MovePlanner::new(Move::to(50_000), 0x000F);
        assert_eq!(
            absolute.next(ENABLED | TARGET_REACHED),
            MoveStep::Send(0x3F)
        );
        assert_eq!(absolute.next(ENABLED | TARGET_REACHED), MoveStep::Wait);
        assert_eq!(
            absolute.next(ENABLED | SET_POINT_ACKNOWLEDGE),
            MoveStep::Send(0x2F)
        );
        assert_eq!(
            absolute.next(ENABLED | SET_POINT_ACKNOWLEDGE),
            MoveStep::Wait
        );
        assert_eq!(absolute.next(ENABLED), MoveStep::Wait);
        assert_eq!(
            absolute.next(0xD437 & !SET_POINT_ACKNOWLEDGE),
            MoveStep::Done
        );

        let mut relative = MovePlanner::new(Move::by(1_000), 0x000F);
        assert_eq!(relative.next(ENABLED), MoveStep::Send(0x7F));
        let single = Move {
            change_immediately: false,
            ..Move::by(1_000)
        };
        assert_eq!(
            MovePlanner::new(single, 0x0F).next(ENABLED),
            MoveStep::Send(0x5F)
        );
    }

    #[test]
    fn bit_4_left_set_falls_first() {
        let mut planner = MovePlanner::new(Move::to(1), 0x001F);
        assert_eq!(planner.next(ENABLED), MoveStep::Send(0x2F));
        assert_eq!(planner.next(ENABLED), MoveStep::Send(0x3F));
    }

    #[test]
    fn faults_following_errors_and_leaving_operation_enabled_fail_the_move() {
        let mut planner = MovePlanner::new(Move::to(1), 0x000F);
        assert_eq!(
            planner.next(ENABLED | FOLLOWING_ERROR),
            MoveStep::Failed(MoveFailure::FollowingError)
        );
        assert_eq!(planner.next(0x0008), MoveStep::Failed(MoveFailure::Fault));
        assert_eq!(
            planner.next(0x0017),
            MoveStep::Failed(MoveFailure::LeftOperationEnabled)
        );
        assert_eq!(planner.halt(), 0x012F);
    }

    #[test]
    fn soft_limits_in_either_order_and_zero_for_none() {
        let kinco = SoftLimits::between(100_000, -100_000).unwrap();
        assert_eq!(kinco, SoftLimits::between(-100_000, 100_000).unwrap());
        assert!(kinco.allow(100_000) && !kinco.allow(100_001) && !kinco.allow(-100_001));
        assert_eq!(SoftLimits::between(0, 0), None);
    }
}

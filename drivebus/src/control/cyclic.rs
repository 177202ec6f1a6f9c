//! The cyclic synchronous modes (CiA 402-2: csp 8, csv 9, cst 10) as a pure planner for one
//! axis: at every SYNC the master sends a controlword and a set point in an RPDO and reads the
//! statusword and the actual position back from a TPDO. The planner turns each TPDO's feedback
//! and the next trajectory sample into the next RPDO's content:
//!
//! * first it walks the CiA 402 machine to operation enabled through the RPDO's controlword
//!   (the [`Cia402Planner`]), holding the set point (the actual position in csp, zero in csv and
//!   cst) so the axis does not jump when it is enabled;
//! * then it sends the samples, and fails on a fault, on the drive leaving operation enabled,
//!   on the drive's following error (statusword bit 13 in csp), or when the actual position is
//!   further than the following error window from both of the two set points sent last (the
//!   drive has a whole SYNC period to reach one; two cover a TPDO read one cycle late).
//!
//! A mode the drive does not list in 6502h is refused before anything is sent
//! ([`CyclicAxis::new`]). On a failure the caller sends [`CyclicAxis::stop`] (quick stop,
//! holding the set point), so the axis is never left enabled following a stale trajectory.

use super::cia402::command::{ENABLE_OPERATION, QUICK_STOP};
use super::cia402::{Blocker, Cia402Planner, Observation, Step, Target};
use super::mode_bits::{
    CYCLIC_SYNC_POSITION, CYCLIC_SYNC_TORQUE, CYCLIC_SYNC_VELOCITY, FOLLOWING_ERROR,
};
use super::position::{failure, MoveFailure};
use super::quirks::Quirks;
use super::Millis;

/// A cyclic synchronous mode of operation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CyclicMode {
    /// Cyclic synchronous position (8): set points are target positions (607Ah).
    Position,
    /// Cyclic synchronous velocity (9): set points are target velocities (60FFh).
    Velocity,
    /// Cyclic synchronous torque (10): set points are target torques (6071h).
    Torque,
}

impl CyclicMode {
    /// The mode's number in 6060h.
    pub const fn number(self) -> i8 {
        match self {
            CyclicMode::Position => CYCLIC_SYNC_POSITION,
            CyclicMode::Velocity => CYCLIC_SYNC_VELOCITY,
            CyclicMode::Torque => CYCLIC_SYNC_TORQUE,
        }
    }

    /// The mode's bit in the supported drive modes (6502h: csp 7, csv 8, cst 9).
    pub const fn supported_bit(self) -> u32 {
        match self {
            CyclicMode::Position => 1 << 7,
            CyclicMode::Velocity => 1 << 8,
            CyclicMode::Torque => 1 << 9,
        }
    }
}

/// What the drive sent back in its TPDO at a SYNC.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Feedback {
    /// The statusword (6041h).
    pub statusword: u16,
    /// The position actual value (6064h).
    pub actual: i32,
}

impl Feedback {
    /// The feedback a TPDO mapping the statusword then the position actual value carries
    /// (2 + 4 bytes, little-endian, as CiA 301 maps them); `None` for a shorter payload.
    pub fn from_tpdo(payload: &[u8]) -> Option<Self> {
        let statusword = u16::from_le_bytes(payload.get(0..2)?.try_into().ok()?);
        let actual = i32::from_le_bytes(payload.get(2..6)?.try_into().ok()?);
        Some(Self { statusword, actual })
    }
}

/// What to send in the RPDO before the next SYNC.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Command {
    /// The controlword (6040h).
    pub controlword: u16,
    /// The set point: a position, velocity or torque as the mode says.
    pub set_point: i32,
}

impl Command {
    /// The RPDO payload mapping the controlword then the set point, little-endian: 6 bytes
    /// (position, velocity: 32 bits), or 4 in cst (the target torque 6071h is 16 bits; the set
    /// point is saturated to it). Returns the buffer and the length used.
    pub fn rpdo_payload(&self, mode: CyclicMode) -> ([u8; 6], usize) {
        let mut out = [0u8; 6];
        out[0..2].copy_from_slice(&self.controlword.to_le_bytes());
        match mode {
            CyclicMode::Torque => {
                let torque = self.set_point.clamp(i16::MIN.into(), i16::MAX.into()) as i16;
                out[2..4].copy_from_slice(&torque.to_le_bytes());
                (out, 4)
            }
            CyclicMode::Position | CyclicMode::Velocity => {
                out[2..6].copy_from_slice(&self.set_point.to_le_bytes());
                (out, 6)
            }
        }
    }
}

/// Why a cyclic run cannot start or stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CyclicFailure {
    /// Refused before anything was sent: the drive does not list the mode in 6502h.
    ModeNotSupported {
        /// The mode asked for.
        mode: CyclicMode,
        /// The supported drive modes (6502h) the drive reported.
        supported: u32,
    },
    /// The drive cannot be brought to operation enabled.
    Blocked(Blocker),
    /// The drive faulted (statusword bit 3).
    Fault {
        /// The statusword that reported it.
        status: u16,
    },
    /// The drive left operation enabled without a fault (quick stop, disable).
    LeftOperationEnabled {
        /// The statusword that reported it.
        status: u16,
    },
    /// The following error exceeded its window: the drive said so (statusword bit 13), or the
    /// actual position was beyond the window from the set points sent.
    FollowingError {
        /// The statusword of the TPDO that showed it.
        status: u16,
        /// The actual position minus the nearer of the last two set points sent.
        error: i64,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Enabling,
    Following,
}

/// The planner of one axis in a cyclic synchronous mode.
#[derive(Debug, Clone)]
pub struct CyclicAxis {
    mode: CyclicMode,
    planner: Cia402Planner,
    phase: Phase,
    window: Option<u32>,
    controlword: u16,
    /// The set points sent last and the one before, newest first.
    sent: [Option<i32>; 2],
}

impl CyclicAxis {
    /// An axis in `mode`, given the drive's supported modes (6502h), its quirks and its
    /// following error window (6065h; `None` or `u32::MAX`: no check by the master). Refuses a
    /// mode the drive does not list.
    pub fn new(
        mode: CyclicMode,
        supported: u32,
        quirks: Quirks,
        window: Option<u32>,
    ) -> Result<Self, CyclicFailure> {
        if supported & mode.supported_bit() == 0 {
            return Err(CyclicFailure::ModeNotSupported { mode, supported });
        }
        Ok(Self {
            mode,
            planner: Cia402Planner::new(quirks),
            phase: Phase::Enabling,
            window: window.filter(|w| *w != u32::MAX),
            controlword: 0,
            sent: [None; 2],
        })
    }

    /// The mode.
    pub const fn mode(&self) -> CyclicMode {
        self.mode
    }

    /// Whether the axis is operation enabled and takes the samples.
    pub fn following(&self) -> bool {
        self.phase == Phase::Following
    }

    /// The set point that keeps the axis where it is: its actual position in csp, zero else.
    fn hold(&self, feedback: Feedback) -> i32 {
        match self.mode {
            CyclicMode::Position => self.sent[0].unwrap_or(feedback.actual),
            CyclicMode::Velocity | CyclicMode::Torque => 0,
        }
    }

    fn command(&mut self, controlword: u16, set_point: i32) -> Command {
        self.controlword = controlword;
        self.sent = [Some(set_point), self.sent[0]];
        Command {
            controlword,
            set_point,
        }
    }

    /// The RPDO content for the next SYNC, given the TPDO `feedback` of this one, the next
    /// trajectory `sample` (taken once following; `None` holds the last set point) and the
    /// time.
    pub fn cycle(
        &mut self,
        feedback: Feedback,
        sample: Option<i32>,
        now: Millis,
    ) -> Result<Command, CyclicFailure> {
        match self.phase {
            Phase::Enabling => self.enable(feedback, now),
            Phase::Following => {
                self.check(feedback)?;
                let set_point = sample.unwrap_or_else(|| self.hold(feedback));
                Ok(self.command(ENABLE_OPERATION, set_point))
            }
        }
    }

    /// One step of the walk to operation enabled, holding the set point.
    fn enable(&mut self, feedback: Feedback, now: Millis) -> Result<Command, CyclicFailure> {
        let seen = Observation {
            statusword: feedback.statusword,
            safe_torque_off: false,
            now,
        };
        let hold = match self.mode {
            // Until enabled the drive's position is the one to hold.
            CyclicMode::Position => feedback.actual,
            CyclicMode::Velocity | CyclicMode::Torque => 0,
        };
        let controlword = match self.planner.next(&seen, Target::OperationEnabled) {
            Step::Done => {
                self.phase = Phase::Following;
                ENABLE_OPERATION
            }
            Step::Send { controlword, .. } => {
                self.planner.sent(controlword, now);
                controlword
            }
            Step::Wait(_) => self.controlword,
            Step::Blocked(blocker) => return Err(CyclicFailure::Blocked(blocker)),
        };
        Ok(self.command(controlword, hold))
    }

    /// The failures a TPDO shows while following.
    fn check(&self, feedback: Feedback) -> Result<(), CyclicFailure> {
        let status = feedback.statusword;
        let error_bit = match self.mode {
            CyclicMode::Position => FOLLOWING_ERROR,
            CyclicMode::Velocity | CyclicMode::Torque => 0,
        };
        let error = self.following_error(feedback.actual);
        match failure(status, error_bit) {
            Some(MoveFailure::Fault) => return Err(CyclicFailure::Fault { status }),
            Some(MoveFailure::LeftOperationEnabled) => {
                return Err(CyclicFailure::LeftOperationEnabled { status })
            }
            Some(MoveFailure::FollowingError) => {
                return Err(CyclicFailure::FollowingError { status, error })
            }
            None => {}
        }
        match self.window {
            Some(window)
                if self.mode == CyclicMode::Position
                    && error.unsigned_abs() > u64::from(window) =>
            {
                Err(CyclicFailure::FollowingError { status, error })
            }
            _ => Ok(()),
        }
    }

    /// The actual position minus the nearer of the last two set points sent (0 in csv, cst).
    pub fn following_error(&self, actual: i32) -> i64 {
        if self.mode != CyclicMode::Position {
            return 0;
        }
        self.sent
            .iter()
            .flatten()
            .map(|&s| i64::from(actual) - i64::from(s))
            .min_by_key(|e| e.unsigned_abs())
            .unwrap_or(0)
    }

    /// The RPDO content that stops the axis after a failure or at the end of a run: quick stop,
    /// holding the set point.
    pub fn stop(&self, feedback: Feedback) -> Command {
        Command {
            controlword: QUICK_STOP,
            set_point: self.hold(feedback),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: u32 = 0x0380;
    const ENABLED: u16 = 0x1237;

    fn axis(mode: CyclicMode) -> CyclicAxis {
        CyclicAxis::new(mode, ALL, Quirks::STANDARD, Some(100)).unwrap()
    }

    fn seen(statusword: u16, actual: i32) -> Feedback {
        Feedback { statusword, actual }
    }

    #[test]
    fn payloads_are_little_endian_and_short_tpdos_are_refused() {
        let feedback = Feedback::from_tpdo(&[0x37, 0x12, 0x10, 0x27, 0, 0, 9]).unwrap();
        assert_eq!(feedback, seen(ENABLED, 10_000));
        assert_eq!(Feedback::from_tpdo(&[0x37, 0x12, 0x10, 0x27, 0]), None);
        let command = Command {
            controlword: 0x0F,
            set_point: -2,
        };
        let (bytes, len) = command.rpdo_payload(CyclicMode::Position);
        assert_eq!(&bytes[..len], [0x0F, 0, 0xFE, 0xFF, 0xFF, 0xFF]);
        let big = Command {
            set_point: 40_000,
            ..command
        };
        let (bytes, len) = big.rpdo_payload(CyclicMode::Torque);
        assert_eq!(&bytes[..len], [0x0F, 0, 0xFF, 0x7F]);
    }

    #[test]
    fn a_mode_the_drive_does_not_list_is_refused() {
        assert_eq!(
            CyclicAxis::new(CyclicMode::Torque, 0x0180, Quirks::STANDARD, None).unwrap_err(),
            CyclicFailure::ModeNotSupported {
                mode: CyclicMode::Torque,
                supported: 0x0180
            }
        );
        assert_eq!(CyclicMode::Velocity.number(), 9);
    }

    #[test]
    fn the_axis_is_enabled_through_the_rpdo_holding_its_position_then_follows() {
        let mut axis = axis(CyclicMode::Position);
        let t = Millis(0);
        let c = axis.cycle(seen(0x0250, 700), Some(1), t).unwrap();
        assert_eq!((c.controlword, c.set_point), (0x06, 700));
        let c = axis.cycle(seen(0x0231, 700), Some(1), t).unwrap();
        assert_eq!((c.controlword, c.set_point), (0x07, 700));
        let c = axis.cycle(seen(0x0233, 700), Some(1), t).unwrap();
        assert_eq!((c.controlword, c.set_point), (0x0F, 700));
        assert!(!axis.following());
        let c = axis.cycle(seen(ENABLED, 700), Some(750), t).unwrap();
        assert_eq!((c.controlword, c.set_point), (0x0F, 700), "holds once more");
        assert!(axis.following());
        let c = axis.cycle(seen(ENABLED, 700), Some(750), t).unwrap();
        assert_eq!((c.controlword, c.set_point), (0x0F, 750));
        let c = axis.cycle(seen(ENABLED, 750), None, t).unwrap();
        assert_eq!(c.set_point, 750, "the end of the trajectory is held");
    }

    #[test]
    fn faults_following_errors_and_leaving_enabled_stop_the_run() {
        let mut axis = axis(CyclicMode::Position);
        for status in [0x0250, 0x0231, 0x0233, ENABLED] {
            axis.cycle(seen(status, 0), None, Millis(0)).unwrap();
        }
        axis.cycle(seen(ENABLED, 0), Some(50), Millis(0)).unwrap();
        assert_eq!(
            axis.cycle(seen(ENABLED | FOLLOWING_ERROR, 0), Some(100), Millis(0)),
            Err(CyclicFailure::FollowingError {
                status: ENABLED | FOLLOWING_ERROR,
                error: 0
            })
        );
        assert_eq!(
            axis.cycle(seen(ENABLED, 300), Some(100), Millis(0)),
            Err(CyclicFailure::FollowingError {
                status: ENABLED,
                error: 250
            }),
            "beyond the window from both set points"
        );
        assert_eq!(
            axis.cycle(seen(0x0218, 0), Some(100), Millis(0)),
            Err(CyclicFailure::Fault { status: 0x0218 })
        );
        assert_eq!(
            axis.cycle(seen(0x0217, 0), Some(100), Millis(0)),
            Err(CyclicFailure::LeftOperationEnabled { status: 0x0217 })
        );
        let stop = axis.stop(seen(ENABLED, 40));
        assert_eq!((stop.controlword, stop.set_point), (0x02, 50));
    }

    #[test]
    fn velocity_holds_zero_and_has_no_position_check() {
        let mut axis = axis(CyclicMode::Velocity);
        for status in [0x0250, 0x0231, 0x0233, ENABLED] {
            let c = axis.cycle(seen(status, 5_000), None, Millis(0)).unwrap();
            assert_eq!(c.set_point, 0);
        }
        let c = axis.cycle(seen(ENABLED | FOLLOWING_ERROR, 90_000), Some(-3), Millis(0));
        assert_eq!(c.unwrap().set_point, -3, "bit 13 is reserved in csv");
        assert_eq!(axis.stop(seen(ENABLED, 1)).set_point, 0);
    }
}

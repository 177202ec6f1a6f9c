//! What a control driver decides between two polls, without I/O and without a clock: the steps
//! the blocking driver (`driver`) and the async one (`async_driver`) both take, so the two differ
//! only in how they read, write and wait.
//!
//! A driver reads the status, hands it to a walk ([`Cia402Walk::step`], [`MachineWalk::step`]),
//! writes the command the step names (if any), and, once its deadline has passed, fails with the
//! step's error; otherwise it waits one poll interval and reads again.

use core::time::Duration;

use super::cia402::{self, Blocker, Cia402Planner, Observation, State, Step, Target, Waiting};
use super::control_error::{ControlError, StuckReason};
use super::machine::{Machine, Plan, TransitionKind};
use super::quirks::Quirks;
use super::stop_option::QuickStopEnd;
use super::Millis;

/// Pause between two status polls.
pub const POLL_INTERVAL: Duration = Duration::from_millis(1);

/// One step of a walk towards a target state.
#[derive(Debug, Clone, PartialEq)]
pub enum Walk {
    /// The drive is in the target state.
    Done,
    /// The walk cannot go on: the error says why.
    Failed(ControlError),
    /// Not there yet: write `write` (if any), then poll again, or fail with `if_late` once the
    /// deadline has passed.
    Pending {
        /// The command to write now.
        write: Option<u16>,
        /// Why the drive is not there yet, as the error the deadline ends the walk with.
        if_late: ControlError,
    },
}

/// Writes a command unless the same one was already written while the drive showed the same
/// status: a drive slow to take a transition is not flooded with the command.
#[derive(Debug, Clone, Default)]
struct Commander {
    last: Option<(u16, u16)>,
}

impl Commander {
    fn should_write(&mut self, command: u16, status: u16) -> bool {
        let fresh = self.last != Some((command, status));
        self.last = Some((command, status));
        fresh
    }
}

/// The steps of a walk on the CiA 402 machine, which both drivers run the same way: a walk to a
/// target ([`Cia402Walk`]) or a quick stop seen through to its end ([`QuickStopWalk`]).
pub trait Cia402Steps {
    /// What to do after observing `seen`.
    fn step(&mut self, seen: &Observation) -> Walk;
    /// Records that the step's command was written at `now`.
    fn sent(&mut self, controlword: u16, now: Millis);
}

impl Cia402Steps for Cia402Walk {
    fn step(&mut self, seen: &Observation) -> Walk {
        Cia402Walk::step(self, seen)
    }
    fn sent(&mut self, controlword: u16, now: Millis) {
        Cia402Walk::sent(self, controlword, now);
    }
}

impl Cia402Steps for QuickStopWalk {
    fn step(&mut self, seen: &Observation) -> Walk {
        QuickStopWalk::step(self, seen)
    }
    fn sent(&mut self, controlword: u16, now: Millis) {
        QuickStopWalk::sent(self, controlword, now);
    }
}

/// A walk of the CiA 402 machine to a target, over the [`Cia402Planner`].
#[derive(Debug, Clone)]
pub struct Cia402Walk {
    planner: Cia402Planner,
    commander: Commander,
    target: Target,
}

impl Cia402Walk {
    /// A walk to `target` of a drive with `quirks` whose controlword reads `controlword` at `now`.
    pub fn new(quirks: Quirks, target: Target, controlword: u16, now: Millis) -> Self {
        let mut planner = Cia402Planner::new(quirks);
        planner.sent(controlword, now);
        Self {
            planner,
            commander: Commander::default(),
            target,
        }
    }

    /// What to do after observing `seen`.
    pub fn step(&mut self, seen: &Observation) -> Walk {
        let stuck = |reason| ControlError::Stuck {
            target: self.target.state().name(),
            state: State::decode(seen.statusword).map(State::name),
            status: seen.statusword,
            reason,
        };
        match self.planner.next(seen, self.target) {
            Step::Done => Walk::Done,
            Step::Send {
                controlword,
                transition,
            } => Walk::Pending {
                write: self
                    .commander
                    .should_write(controlword, seen.statusword)
                    .then_some(controlword),
                if_late: stuck(StuckReason::NoResponse {
                    transition,
                    command: controlword,
                }),
            },
            Step::Wait(waiting) => Walk::Pending {
                write: None,
                if_late: stuck(StuckReason::Waiting(waiting)),
            },
            Step::Blocked(blocker) if blocker.is_final() => {
                Walk::Failed(stuck(StuckReason::Blocked(blocker)))
            }
            Step::Blocked(blocker) => Walk::Pending {
                write: None,
                if_late: stuck(StuckReason::Blocked(blocker)),
            },
        }
    }

    /// Records that the step's command was written at `now`.
    pub fn sent(&mut self, controlword: u16, now: Millis) {
        self.planner.sent(controlword, now);
    }
}

/// The target of a quick stop from `state`: quick stop active from operation enabled, switch on
/// disabled from anywhere else.
pub fn quick_stop_target(state: Option<State>) -> Target {
    match state {
        Some(State::OperationEnabled) => Target::QuickStopActive,
        _ => Target::SwitchOnDisabled,
    }
}

/// A quick stop's outcome: a drive whose quick stop option code ends in switch on disabled
/// counts as stopped there too.
pub fn quick_stop_outcome(outcome: Result<(), ControlError>) -> Result<(), ControlError> {
    match outcome {
        Err(ControlError::Stuck {
            reason: StuckReason::Blocked(Blocker::QuickStopOnlyFromOperationEnabled),
            state: Some(name),
            ..
        }) if name == State::SwitchOnDisabled.name() => Ok(()),
        other => other,
    }
}

/// A quick stop seen through to the end its option code gives: from operation enabled the
/// quick stop command (to quick stop active), then, where the code ends in switch on disabled,
/// the wait for the drive's own transition 12 once it has stopped; nothing is written while
/// the drive brakes (disable voltage would cut the power mid-ramp). From any other state it
/// disables, as [`quick_stop_target`] says.
///
/// The end may start open ([`QuickStopEnd::Either`]) and be narrowed once the command has gone
/// out ([`wants_end`](QuickStopWalk::wants_end), [`narrow`](QuickStopWalk::narrow)): the end only
/// decides what the walk waits for after the command, so a read of the option code comes after
/// it and never holds it back.
#[derive(Debug, Clone)]
pub struct QuickStopWalk {
    walk: Cia402Walk,
    end: QuickStopEnd,
    /// Whether a command has gone out (the quick stop, from operation enabled).
    commanded: bool,
    /// Whether the end was narrowed (or tried to be): the code is read once.
    narrowed: bool,
}

impl QuickStopWalk {
    /// A quick stop of a drive with `quirks` in `state` whose quick stop ends at `end`, its
    /// controlword reading `controlword` at `now`.
    pub fn new(
        quirks: Quirks,
        end: QuickStopEnd,
        state: Option<State>,
        controlword: u16,
        now: Millis,
    ) -> Self {
        let first = quick_stop_target(state);
        let end = if first == Target::QuickStopActive {
            end
        } else {
            QuickStopEnd::SwitchOnDisabled
        };
        Self {
            walk: Cia402Walk::new(quirks, first, controlword, now),
            end,
            commanded: false,
            narrowed: false,
        }
    }

    /// Whether the walk wants its end now: it is open ([`QuickStopEnd::Either`]), its command
    /// has gone out, and it was not narrowed yet. A driver then reads the option code (605Ah)
    /// and hands the end it gives to [`narrow`](QuickStopWalk::narrow).
    pub fn wants_end(&self) -> bool {
        self.end == QuickStopEnd::Either && self.commanded && !self.narrowed
    }

    /// Narrows an open end to `end` (a failed read gives [`QuickStopEnd::Either`], which keeps
    /// it open); an end already known is kept. Asked once: later calls change nothing.
    pub fn narrow(&mut self, end: QuickStopEnd) {
        if self.end == QuickStopEnd::Either && !self.narrowed {
            self.end = end;
        }
        self.narrowed = true;
    }

    /// What to do after observing `seen`.
    pub fn step(&mut self, seen: &Observation) -> Walk {
        let state = State::decode(seen.statusword);
        match (self.end, state) {
            (
                QuickStopEnd::SwitchOnDisabled | QuickStopEnd::Either,
                Some(State::SwitchOnDisabled),
            ) => Walk::Done,
            (QuickStopEnd::SwitchOnDisabled, Some(State::QuickStopActive)) => Walk::Pending {
                write: None,
                if_late: ControlError::Stuck {
                    target: State::SwitchOnDisabled.name(),
                    state: state.map(State::name),
                    status: seen.statusword,
                    reason: cia402::transition("12").map_or(StuckReason::Unreachable, |t| {
                        StuckReason::Waiting(Waiting::Automatic(t))
                    }),
                },
            },
            _ => self.walk.step(seen),
        }
    }

    /// Records that the step's command was written at `now`.
    pub fn sent(&mut self, controlword: u16, now: Millis) {
        self.commanded = true;
        self.walk.sent(controlword, now);
    }
}

/// Whether a fault reset has anything to do in `state` (fault or fault reaction active).
pub fn needs_fault_reset(state: Option<State>) -> bool {
    matches!(state, Some(State::Fault | State::FaultReactionActive))
}

/// A walk of a vendor state machine (a [`Machine`] table) to the state called `target`.
#[derive(Debug, Clone)]
pub struct MachineWalk {
    machine: Machine<'static>,
    goal: u8,
    target: &'static str,
    commander: Commander,
}

impl MachineWalk {
    /// A walk of `machine` to its state `target`; [`ControlError::UnknownState`] if it has none.
    pub fn new(machine: Machine<'static>, target: &'static str) -> Result<Self, ControlError> {
        let goal = machine
            .state_index(target)
            .ok_or(ControlError::UnknownState(target))?;
        Ok(Self {
            machine,
            goal,
            target,
            commander: Commander::default(),
        })
    }

    /// What to do after reading `status` from the status register.
    pub fn step(&mut self, status: u16) -> Walk {
        let machine = self.machine;
        let current = machine.recognise(status);
        let stuck = |reason| ControlError::Stuck {
            target: self.target,
            state: current
                .and_then(|i| machine.states.get(usize::from(i)))
                .map(|s| s.name),
            status,
            reason,
        };
        let pending = |write, reason| Walk::Pending {
            write,
            if_late: stuck(reason),
        };
        match current.map(|from| machine.next(from, self.goal, |_| true)) {
            None => pending(None, StuckReason::UnknownStatus),
            Some(Plan::Done) => Walk::Done,
            Some(Plan::Command(transition)) => {
                let TransitionKind::Command(command) = transition.kind else {
                    return Walk::Failed(stuck(StuckReason::Unreachable));
                };
                let write = self
                    .commander
                    .should_write(command, status)
                    .then_some(command);
                pending(
                    write,
                    StuckReason::NoResponse {
                        transition,
                        command,
                    },
                )
            }
            Some(Plan::Await(transition)) => pending(None, StuckReason::Awaiting(transition)),
            Some(Plan::NeedsExternal(transition)) => {
                Walk::Failed(stuck(StuckReason::NeedsExternal(transition)))
            }
            Some(Plan::Unreachable | Plan::BadTable) => {
                Walk::Failed(stuck(StuckReason::Unreachable))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seen(statusword: u16) -> Observation {
        Observation {
            statusword,
            safe_torque_off: false,
            now: Millis(0),
        }
    }

    const OPERATION_ENABLED: u16 = 0x0037;
    const QUICK_STOP_ACTIVE: u16 = 0x0017;
    const SWITCH_ON_DISABLED: u16 = 0x0040;

    fn quick_stop(end: QuickStopEnd) -> QuickStopWalk {
        let state = Some(State::OperationEnabled);
        QuickStopWalk::new(Quirks::STANDARD, end, state, 0x0F, Millis(0))
    }

    #[test]
    fn a_quick_stop_ending_switched_off_commands_once_then_waits_for_transition_12() {
        let mut walk = quick_stop(QuickStopEnd::SwitchOnDisabled);
        match walk.step(&seen(OPERATION_ENABLED)) {
            Walk::Pending { write, .. } => assert_eq!(write, Some(0x02), "quick stop"),
            other => panic!("{other:?}"),
        }
        walk.sent(0x02, Millis(1));
        // Braking in quick stop active: nothing written, and a deadline names transition 12.
        match walk.step(&seen(QUICK_STOP_ACTIVE)) {
            Walk::Pending {
                write: None,
                if_late:
                    ControlError::Stuck {
                        reason: StuckReason::Waiting(Waiting::Automatic(t)),
                        ..
                    },
            } => assert_eq!(t.name, "12"),
            other => panic!("{other:?}"),
        }
        assert_eq!(walk.step(&seen(SWITCH_ON_DISABLED)), Walk::Done);
    }

    #[test]
    fn a_quick_stop_ending_in_quick_stop_active_fails_if_the_drive_switches_off() {
        let mut walk = quick_stop(QuickStopEnd::QuickStopActive);
        assert_eq!(walk.step(&seen(QUICK_STOP_ACTIVE)), Walk::Done);
        let mut walk = quick_stop(QuickStopEnd::QuickStopActive);
        assert!(matches!(
            walk.step(&seen(SWITCH_ON_DISABLED)),
            Walk::Failed(ControlError::Stuck { .. })
        ));
        let mut either = quick_stop(QuickStopEnd::Either);
        assert_eq!(either.step(&seen(SWITCH_ON_DISABLED)), Walk::Done);
        assert_eq!(either.step(&seen(QUICK_STOP_ACTIVE)), Walk::Done);
    }

    #[test]
    fn an_open_end_wants_the_code_only_after_the_command_then_waits_as_it_says() {
        let mut walk = quick_stop(QuickStopEnd::Either);
        assert!(!walk.wants_end(), "nothing is read before the command");
        match walk.step(&seen(OPERATION_ENABLED)) {
            Walk::Pending { write, .. } => assert_eq!(write, Some(0x02), "quick stop"),
            other => panic!("{other:?}"),
        }
        assert!(!walk.wants_end(), "the command has not gone out yet");
        walk.sent(0x02, Millis(1));
        assert!(walk.wants_end());
        walk.narrow(QuickStopEnd::SwitchOnDisabled);
        assert!(!walk.wants_end(), "the code is read once");
        // Codes 0-4: quick stop active is not the end, the walk waits for transition 12.
        assert!(matches!(
            walk.step(&seen(QUICK_STOP_ACTIVE)),
            Walk::Pending { write: None, .. }
        ));
        assert_eq!(walk.step(&seen(SWITCH_ON_DISABLED)), Walk::Done);
    }

    #[test]
    fn a_failed_read_keeps_the_end_open_and_a_known_end_is_not_narrowed() {
        let mut walk = quick_stop(QuickStopEnd::Either);
        walk.sent(0x02, Millis(1));
        walk.narrow(QuickStopEnd::of_read(None));
        assert!(!walk.wants_end(), "a failed read is not retried");
        assert_eq!(walk.step(&seen(QUICK_STOP_ACTIVE)), Walk::Done);

        let mut known = quick_stop(QuickStopEnd::QuickStopActive);
        known.sent(0x02, Millis(1));
        assert!(!known.wants_end());
        known.narrow(QuickStopEnd::SwitchOnDisabled);
        assert_eq!(known.step(&seen(QUICK_STOP_ACTIVE)), Walk::Done);
    }

    #[test]
    fn a_quick_stop_outside_operation_enabled_disables() {
        let state = Some(State::SwitchedOn);
        let end = QuickStopEnd::QuickStopActive;
        let mut walk = QuickStopWalk::new(Quirks::STANDARD, end, state, 0x07, Millis(0));
        assert_eq!(walk.step(&seen(SWITCH_ON_DISABLED)), Walk::Done);
    }
}

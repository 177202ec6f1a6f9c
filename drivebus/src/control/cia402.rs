//! The CiA 402 power drive system state machine: decoding the statusword, the transition table
//! (transitions 1-16; transition 0 leaves the unobservable start state) and the planner that
//! computes the next controlword towards a target state.
//!
//! What the table alone cannot say is handled here: fault reset acts on a rising edge of
//! controlword bit 7 (held for the drive's minimum time, then dropped to re-arm); halt (bit 8) is
//! carried in every command; safe torque off, voltage enabled (statusword bit 4) and remote
//! (bit 9) block progress with a reason instead of a timeout.

use core::fmt;

use super::machine::{Machine, Plan, StateDef, StatePattern, TransitionDef, TransitionKind};
use super::quirks::Quirks;
use super::Millis;

/// Controlword bit 7: fault reset, acting on its rising edge.
pub const FAULT_RESET_BIT: u16 = 1 << 7;
/// Controlword bit 8: halt.
pub const HALT_BIT: u16 = 1 << 8;
/// Statusword bit 4: voltage enabled.
pub const VOLTAGE_ENABLED_BIT: u16 = 1 << 4;
/// Statusword bit 9: remote (the controlword is processed).
pub const REMOTE_BIT: u16 = 1 << 9;

/// Device control commands (controlword bits 0-3 and 7).
pub mod command {
    /// Shutdown: transitions 2, 6, 8.
    pub const SHUTDOWN: u16 = 0x0006;
    /// Switch on: transition 3; also disable operation, transition 5.
    pub const SWITCH_ON: u16 = 0x0007;
    /// Enable operation: transitions 4 and 16.
    pub const ENABLE_OPERATION: u16 = 0x000F;
    /// Disable voltage: transitions 7, 9, 10, 12.
    pub const DISABLE_VOLTAGE: u16 = 0x0000;
    /// Quick stop: transition 11 (and 7, 10).
    pub const QUICK_STOP: u16 = 0x0002;
    /// Fault reset: transition 15, on the rising edge.
    pub const FAULT_RESET: u16 = super::FAULT_RESET_BIT;
}

/// A state of the CiA 402 power drive system.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum State {
    /// Not ready to switch on (`x0xx 0000`).
    NotReadyToSwitchOn,
    /// Switch on disabled (`x1xx 0000`).
    SwitchOnDisabled,
    /// Ready to switch on (`x01x 0001`).
    ReadyToSwitchOn,
    /// Switched on (`x01x 0011`).
    SwitchedOn,
    /// Operation enabled (`x01x 0111`).
    OperationEnabled,
    /// Quick stop active (`x00x 0111`).
    QuickStopActive,
    /// Fault reaction active (`x0xx 1111`).
    FaultReactionActive,
    /// Fault (`x0xx 1000`).
    Fault,
}

impl State {
    /// Every state, in [`TABLE`] order.
    pub const ALL: [State; 8] = [
        State::NotReadyToSwitchOn,
        State::SwitchOnDisabled,
        State::ReadyToSwitchOn,
        State::SwitchedOn,
        State::OperationEnabled,
        State::QuickStopActive,
        State::FaultReactionActive,
        State::Fault,
    ];

    /// The state a statusword shows, or `None` for a bit pattern CiA 402 does not define.
    pub fn decode(statusword: u16) -> Option<State> {
        let index = TABLE.recognise(statusword)?;
        State::ALL.get(usize::from(index)).copied()
    }

    /// Index of the state in [`TABLE`].
    pub const fn index(self) -> u8 {
        self as u8
    }

    /// Name as in CiA 402.
    pub const fn name(self) -> &'static str {
        TABLE.states[self as usize].name
    }
}

impl fmt::Display for State {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A state the master can ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Target {
    /// Switch on disabled: no voltage on the motor.
    SwitchOnDisabled,
    /// Ready to switch on.
    ReadyToSwitchOn,
    /// Switched on: power stage on, no torque.
    SwitchedOn,
    /// Operation enabled: the drive follows its setpoints.
    OperationEnabled,
    /// Quick stop active: reached only from operation enabled.
    QuickStopActive,
}

impl Target {
    /// Every target.
    pub const ALL: [Target; 5] = [
        Target::SwitchOnDisabled,
        Target::ReadyToSwitchOn,
        Target::SwitchedOn,
        Target::OperationEnabled,
        Target::QuickStopActive,
    ];

    /// The state this target is.
    pub const fn state(self) -> State {
        match self {
            Target::SwitchOnDisabled => State::SwitchOnDisabled,
            Target::ReadyToSwitchOn => State::ReadyToSwitchOn,
            Target::SwitchedOn => State::SwitchedOn,
            Target::OperationEnabled => State::OperationEnabled,
            Target::QuickStopActive => State::QuickStopActive,
        }
    }
}

const fn sw(mask: u16, value: u16) -> StatePattern {
    StatePattern { mask, value }
}

const fn hop(
    name: &'static str,
    from: State,
    to: State,
    kind: TransitionKind,
) -> TransitionDef<'static> {
    TransitionDef {
        name,
        from: from as u8,
        to: to as u8,
        kind,
        doc: "",
    }
}

const fn cmd(name: &'static str, from: State, to: State, value: u16) -> TransitionDef<'static> {
    hop(name, from, to, TransitionKind::Command(value))
}

use State::*;

/// The CiA 402 state machine as a [`Machine`] table; state indices follow [`State::ALL`].
pub const TABLE: Machine = Machine {
    states: &[
        StateDef {
            name: "not ready to switch on",
            patterns: &[sw(0x4F, 0x00)],
        },
        StateDef {
            name: "switch on disabled",
            patterns: &[sw(0x4F, 0x40)],
        },
        StateDef {
            name: "ready to switch on",
            patterns: &[sw(0x6F, 0x21)],
        },
        StateDef {
            name: "switched on",
            patterns: &[sw(0x6F, 0x23)],
        },
        StateDef {
            name: "operation enabled",
            patterns: &[sw(0x6F, 0x27)],
        },
        StateDef {
            name: "quick stop active",
            patterns: &[sw(0x6F, 0x07)],
        },
        StateDef {
            name: "fault reaction active",
            patterns: &[sw(0x4F, 0x0F)],
        },
        StateDef {
            name: "fault",
            patterns: &[sw(0x4F, 0x08)],
        },
    ],
    transitions: &[
        hop(
            "1",
            NotReadyToSwitchOn,
            SwitchOnDisabled,
            TransitionKind::Automatic,
        ),
        cmd("2", SwitchOnDisabled, ReadyToSwitchOn, command::SHUTDOWN),
        cmd("3", ReadyToSwitchOn, SwitchedOn, command::SWITCH_ON),
        cmd("4", SwitchedOn, OperationEnabled, command::ENABLE_OPERATION),
        cmd("5", OperationEnabled, SwitchedOn, command::SWITCH_ON),
        cmd("6", SwitchedOn, ReadyToSwitchOn, command::SHUTDOWN),
        cmd(
            "7",
            ReadyToSwitchOn,
            SwitchOnDisabled,
            command::DISABLE_VOLTAGE,
        ),
        cmd("8", OperationEnabled, ReadyToSwitchOn, command::SHUTDOWN),
        cmd(
            "9",
            OperationEnabled,
            SwitchOnDisabled,
            command::DISABLE_VOLTAGE,
        ),
        cmd("10", SwitchedOn, SwitchOnDisabled, command::DISABLE_VOLTAGE),
        cmd("11", OperationEnabled, QuickStopActive, command::QUICK_STOP),
        cmd(
            "12",
            QuickStopActive,
            SwitchOnDisabled,
            command::DISABLE_VOLTAGE,
        ),
        hop(
            "13",
            NotReadyToSwitchOn,
            FaultReactionActive,
            TransitionKind::External,
        ),
        hop(
            "13",
            SwitchOnDisabled,
            FaultReactionActive,
            TransitionKind::External,
        ),
        hop(
            "13",
            ReadyToSwitchOn,
            FaultReactionActive,
            TransitionKind::External,
        ),
        hop(
            "13",
            SwitchedOn,
            FaultReactionActive,
            TransitionKind::External,
        ),
        hop(
            "13",
            OperationEnabled,
            FaultReactionActive,
            TransitionKind::External,
        ),
        hop(
            "13",
            QuickStopActive,
            FaultReactionActive,
            TransitionKind::External,
        ),
        hop("14", FaultReactionActive, Fault, TransitionKind::Automatic),
        cmd("15", Fault, SwitchOnDisabled, command::FAULT_RESET),
        cmd(
            "16",
            QuickStopActive,
            OperationEnabled,
            command::ENABLE_OPERATION,
        ),
    ],
};

/// The transition called `name` (the first, for transition 13).
pub fn transition(name: &str) -> Option<&'static TransitionDef<'static>> {
    TABLE.transitions.iter().find(|t| t.name == name)
}

/// What the drive is seen doing in one poll.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Observation {
    /// The statusword (0x6041) as read.
    pub statusword: u16,
    /// Whether safe torque off is active (from the description's `sto_bit`; false if none).
    pub safe_torque_off: bool,
    /// When it was read.
    pub now: Millis,
}

/// Why the planner waits without sending anything.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Waiting {
    /// The drive leaves this state by itself (transition 1 or 14).
    Automatic(&'static TransitionDef<'static>),
    /// Fault reset is held high for the drive's minimum time; this many milliseconds remain.
    FaultResetHold {
        /// Milliseconds until the bit may be dropped.
        remaining_ms: u64,
    },
}

impl fmt::Display for Waiting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Waiting::Automatic(t) => {
                write!(
                    f,
                    "waiting for the drive to take transition {} by itself",
                    t.name
                )
            }
            Waiting::FaultResetHold { remaining_ms } => {
                write!(f, "holding fault reset high for {remaining_ms} ms more")
            }
        }
    }
}

/// Why the target cannot be reached from here (now, or at all).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Blocker {
    /// The statusword shows no CiA 402 state.
    UnknownStatusword(u16),
    /// Safe torque off is active: the drive stays in switch on disabled.
    SafeTorqueOff,
    /// Quick stop active is entered only from operation enabled (transition 11).
    QuickStopOnlyFromOperationEnabled,
    /// Switch on needs voltage enabled (statusword bit 4) and the drive reports none.
    VoltageNotEnabled,
    /// The remote bit (statusword bit 9) is clear: the drive ignores the controlword.
    NotRemote,
    /// Only an outside event leads on.
    NeedsExternal(&'static TransitionDef<'static>),
    /// No sequence of commands reaches the target.
    Unreachable,
}

impl Blocker {
    /// Whether waiting cannot help: the driver reports these at once instead of at the deadline.
    pub const fn is_final(&self) -> bool {
        matches!(
            self,
            Blocker::SafeTorqueOff
                | Blocker::QuickStopOnlyFromOperationEnabled
                | Blocker::NeedsExternal(_)
                | Blocker::Unreachable
        )
    }
}

impl fmt::Display for Blocker {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Blocker::UnknownStatusword(w) => {
                write!(f, "statusword {w:#06x} shows no CiA 402 state")
            }
            Blocker::SafeTorqueOff => f.write_str("safe torque off is active"),
            Blocker::QuickStopOnlyFromOperationEnabled => {
                f.write_str("quick stop active is entered only from operation enabled")
            }
            Blocker::VoltageNotEnabled => {
                f.write_str("switch on needs voltage enabled (statusword bit 4), which is clear")
            }
            Blocker::NotRemote => f.write_str(
                "the remote bit (statusword bit 9) is clear: the controlword is ignored",
            ),
            Blocker::NeedsExternal(t) => write!(f, "transition {} needs an outside event", t.name),
            Blocker::Unreachable => f.write_str("no sequence of commands reaches the target"),
        }
    }
}

/// The planner's answer for one observation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step {
    /// The drive is in the target state.
    Done,
    /// Write this controlword; it serves `transition` (for transition 15, the write may be the
    /// drop of bit 7 that re-arms the rising edge).
    Send {
        /// The value for 0x6040.
        controlword: u16,
        /// The transition it serves.
        transition: &'static TransitionDef<'static>,
    },
    /// Send nothing and poll again.
    Wait(Waiting),
    /// The target cannot be reached now.
    Blocked(Blocker),
}

/// Computes the next controlword towards a target; remembers what was sent (for the fault reset
/// edge) but reads no clock and does no I/O.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cia402Planner {
    quirks: Quirks,
    halt: bool,
    last_controlword: Option<u16>,
    fault_reset_raised: Option<Millis>,
}

impl Cia402Planner {
    /// A planner for a drive with `quirks` that knows nothing of the controlword yet.
    pub const fn new(quirks: Quirks) -> Self {
        Self {
            quirks,
            halt: false,
            last_controlword: None,
            fault_reset_raised: None,
        }
    }

    /// The drive's quirks.
    pub const fn quirks(&self) -> Quirks {
        self.quirks
    }

    /// Sets halt (controlword bit 8) for the commands planned from now on.
    pub fn set_halt(&mut self, halt: bool) {
        self.halt = halt;
    }

    /// The controlword last written (or read back), if known.
    pub const fn last_controlword(&self) -> Option<u16> {
        self.last_controlword
    }

    /// Records that `controlword` was written (or read from the drive) at `now`.
    pub fn sent(&mut self, controlword: u16, now: Millis) {
        let was_high = self
            .last_controlword
            .is_some_and(|w| w & FAULT_RESET_BIT != 0);
        let is_high = controlword & FAULT_RESET_BIT != 0;
        self.fault_reset_raised = match (was_high, is_high) {
            (false, true) => Some(now),
            (true, true) => self.fault_reset_raised,
            (_, false) => None,
        };
        self.last_controlword = Some(controlword);
    }

    /// The next step from what the drive shows towards `target`.
    pub fn next(&self, seen: &Observation, target: Target) -> Step {
        let Some(state) = State::decode(seen.statusword) else {
            return Step::Blocked(Blocker::UnknownStatusword(seen.statusword));
        };
        if state == target.state() {
            return Step::Done;
        }
        match state {
            State::Fault => return self.fault_reset(seen.now),
            State::NotReadyToSwitchOn | State::FaultReactionActive => {
                return self.plan(state, target, seen.statusword);
            }
            _ => {}
        }
        if target == Target::QuickStopActive && state != State::OperationEnabled {
            return Step::Blocked(Blocker::QuickStopOnlyFromOperationEnabled);
        }
        if seen.safe_torque_off && target != Target::SwitchOnDisabled {
            return Step::Blocked(Blocker::SafeTorqueOff);
        }
        if self.quirks.honours_remote && seen.statusword & REMOTE_BIT == 0 {
            return Step::Blocked(Blocker::NotRemote);
        }
        self.plan(state, target, seen.statusword)
    }

    fn plan(&self, state: State, target: Target, statusword: u16) -> Step {
        let quick_stop_exit = self.quirks.quick_stop_to_operation_enabled;
        let allowed = |t: &TransitionDef| match t.name {
            "11" => target == Target::QuickStopActive,
            "16" => quick_stop_exit,
            _ => true,
        };
        match TABLE.next(state.index(), target.state().index(), allowed) {
            Plan::Done => Step::Done,
            Plan::Command(t) => self.command(t, statusword),
            Plan::Await(t) => Step::Wait(Waiting::Automatic(t)),
            Plan::NeedsExternal(t) => Step::Blocked(Blocker::NeedsExternal(t)),
            Plan::Unreachable | Plan::BadTable => Step::Blocked(Blocker::Unreachable),
        }
    }

    fn command(&self, transition: &'static TransitionDef<'static>, statusword: u16) -> Step {
        let TransitionKind::Command(value) = transition.kind else {
            return Step::Blocked(Blocker::Unreachable);
        };
        let switches_on = transition.to == State::SwitchedOn.index()
            && transition.from == State::ReadyToSwitchOn.index();
        if switches_on
            && self.quirks.switch_on_needs_voltage
            && statusword & VOLTAGE_ENABLED_BIT == 0
        {
            return Step::Blocked(Blocker::VoltageNotEnabled);
        }
        Step::Send {
            controlword: value | self.halt_bit(),
            transition,
        }
    }

    /// Transition 15: raise bit 7 from a known low level, hold it, then drop it to re-arm.
    fn fault_reset(&self, now: Millis) -> Step {
        let Some(reset) = transition("15") else {
            return Step::Blocked(Blocker::Unreachable);
        };
        let low = command::DISABLE_VOLTAGE | self.halt_bit();
        let is_high = self
            .last_controlword
            .is_some_and(|w| w & FAULT_RESET_BIT != 0);
        match (self.last_controlword, self.fault_reset_raised) {
            // Unknown level: drop it first so the next write is a real rising edge.
            (None, _) => Step::Send {
                controlword: low,
                transition: reset,
            },
            (Some(_), Some(raised)) if is_high => {
                let held = now.since(raised);
                let hold = u64::from(self.quirks.fault_reset_hold_ms);
                if held < hold {
                    Step::Wait(Waiting::FaultResetHold {
                        remaining_ms: hold - held,
                    })
                } else {
                    Step::Send {
                        controlword: low,
                        transition: reset,
                    }
                }
            }
            (Some(_), _) if is_high => Step::Send {
                controlword: low,
                transition: reset,
            },
            (Some(_), _) => Step::Send {
                controlword: command::FAULT_RESET | low,
                transition: reset,
            },
        }
    }

    const fn halt_bit(&self) -> u16 {
        if self.halt {
            HALT_BIT
        } else {
            0
        }
    }
}

#[cfg(test)]
#[path = "cia402_tests.rs"]
mod tests;

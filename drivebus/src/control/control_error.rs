//! How a control procedure fails: [`ControlError`], and [`StuckReason`] for a drive that did not
//! reach its target. Shared by the blocking driver and the async one (`no_std`).

use core::fmt;

use super::cia402::{Blocker, Waiting};
use super::machine::TransitionDef;
use crate::error::Error;

/// Why the driver stopped short of its target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StuckReason {
    /// The CiA 402 planner cannot progress.
    Blocked(Blocker),
    /// The planner was still waiting (automatic transition, fault reset hold) at the deadline.
    Waiting(Waiting),
    /// The command was written but the drive did not take the transition before the deadline.
    NoResponse {
        /// The transition asked for.
        transition: &'static TransitionDef<'static>,
        /// The command value written.
        command: u16,
    },
    /// The drive did not take an automatic transition (initialisation) before the deadline.
    Awaiting(&'static TransitionDef<'static>),
    /// A vendor machine needs an outside event (reset input, safety input) to go on.
    NeedsExternal(&'static TransitionDef<'static>),
    /// No transition of the vendor machine leads to the target.
    Unreachable,
    /// The status register shows none of the vendor machine's states.
    UnknownStatus,
}

impl fmt::Display for StuckReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StuckReason::Blocked(b) => b.fmt(f),
            StuckReason::Waiting(w) => write!(f, "deadline passed while {w}"),
            StuckReason::NoResponse {
                transition,
                command,
            } => write!(
                f,
                "wrote {command:#06x} for transition {} but the drive did not take it",
                transition.name
            ),
            StuckReason::Awaiting(t) => {
                write!(
                    f,
                    "the drive did not take transition {} by itself: {}",
                    t.name, t.doc
                )
            }
            StuckReason::NeedsExternal(t) => {
                write!(f, "transition {} needs an outside event: {}", t.name, t.doc)
            }
            StuckReason::Unreachable => f.write_str("no transition leads to the target"),
            StuckReason::UnknownStatus => f.write_str("the status shows no known state"),
        }
    }
}

/// A failed control operation.
#[derive(Debug, Clone, PartialEq)]
pub enum ControlError {
    /// Reading the status or writing a command failed.
    Bus(Error),
    /// The drive did not reach the target.
    Stuck {
        /// The target state's name.
        target: &'static str,
        /// The state the drive was last seen in (`None`: status not recognised).
        state: Option<&'static str>,
        /// The status word last read.
        status: u16,
        /// Why it did not progress.
        reason: StuckReason,
    },
    /// The mode display (0x6061) did not show the requested mode before the deadline.
    ModeNotConfirmed {
        /// The mode written to 0x6060.
        requested: i8,
        /// The mode 0x6061 showed last.
        displayed: i8,
    },
    /// The vendor machine has no state of this name.
    UnknownState(&'static str),
}

impl From<Error> for ControlError {
    fn from(error: Error) -> Self {
        ControlError::Bus(error)
    }
}

impl fmt::Display for ControlError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ControlError::Bus(e) => write!(f, "drive control: {e}"),
            ControlError::Stuck {
                target,
                state,
                status,
                reason,
            } => write!(
                f,
                "drive stuck in {} (status {status:#06x}) on the way to {target}: {reason}",
                state.unwrap_or("an unknown state")
            ),
            ControlError::ModeNotConfirmed {
                requested,
                displayed,
            } => write!(
                f,
                "mode {requested} requested, the mode display still shows {displayed}"
            ),
            ControlError::UnknownState(name) => {
                write!(f, "the state machine has no state {name:?}")
            }
        }
    }
}

impl core::error::Error for ControlError {}

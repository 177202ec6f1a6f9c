//! The blocking driver: walks a drive to a state by polling its status and writing commands until
//! the planner is done or the deadline passes, and says where and why it got stuck.

use core::fmt;
use std::thread;
use std::time::Duration;

/// The deadline type of the driver (re-exported so generated crates need no `std` import).
pub use std::time::Instant;

use super::cia402::{Blocker, Cia402Planner, Observation, State, Step, Target, Waiting};
use super::machine::{Plan, TransitionDef, TransitionKind};
use super::mode::{self, ModeStep};
use super::objects::{Cia402Modes, Cia402Objects, VendorMachine};
use super::Millis;
use crate::device::Device;
use crate::error::Error;
use crate::link::Link;
use crate::parameter::{OpenEnum, Readable, Writable};

/// Pause between two status polls when nothing was written.
pub const POLL_INTERVAL: Duration = Duration::from_millis(1);

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

impl std::error::Error for ControlError {}

/// Milliseconds since the driver started, the time the pure core sees.
struct Clock(Instant);

impl Clock {
    fn now(&self) -> Millis {
        Millis(u64::try_from(self.0.elapsed().as_millis()).unwrap_or(u64::MAX))
    }
}

/// Writes a command unless the same one was already written while the drive showed the same status.
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

/// Brings a CiA 402 drive to `target`, polling the statusword until `deadline`.
pub fn drive_to<O, L>(
    device: &mut Device<L>,
    target: Target,
    deadline: Instant,
) -> Result<(), ControlError>
where
    O: Cia402Objects,
    L: Link,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::Statusword: Readable<L::Protocol>,
    O::SafeTorqueOffWord: Readable<L::Protocol>,
{
    drive_to_with::<O, L>(device, target, deadline, |device| {
        device.read_raw::<O::Statusword>()
    })
}

/// [`drive_to`] with the statusword taken from `statusword` instead of a read of 0x6041: for
/// example the latest value of a TPDO the application receives.
pub fn drive_to_with<O, L>(
    device: &mut Device<L>,
    target: Target,
    deadline: Instant,
    mut statusword: impl FnMut(&mut Device<L>) -> Result<u16, Error>,
) -> Result<(), ControlError>
where
    O: Cia402Objects,
    L: Link,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::SafeTorqueOffWord: Readable<L::Protocol>,
{
    let clock = Clock(Instant::now());
    let mut planner = Cia402Planner::new(O::QUIRKS);
    planner.sent(device.read_raw::<O::Controlword>()?, clock.now());
    let mut commander = Commander { last: None };
    loop {
        let seen = observe::<O, L>(device, &clock, &mut statusword)?;
        let stuck = |reason| ControlError::Stuck {
            target: target.state().name(),
            state: State::decode(seen.statusword).map(State::name),
            status: seen.statusword,
            reason,
        };
        let reason = match planner.next(&seen, target) {
            Step::Done => return Ok(()),
            Step::Send {
                controlword,
                transition,
            } => {
                if commander.should_write(controlword, seen.statusword) {
                    device.write_raw::<O::Controlword>(controlword)?;
                    planner.sent(controlword, clock.now());
                }
                StuckReason::NoResponse {
                    transition,
                    command: controlword,
                }
            }
            Step::Wait(waiting) => StuckReason::Waiting(waiting),
            Step::Blocked(blocker) if blocker.is_final() => {
                return Err(stuck(StuckReason::Blocked(blocker)))
            }
            Step::Blocked(blocker) => StuckReason::Blocked(blocker),
        };
        if Instant::now() >= deadline {
            return Err(stuck(reason));
        }
        thread::sleep(POLL_INTERVAL);
    }
}

fn observe<O, L>(
    device: &mut Device<L>,
    clock: &Clock,
    statusword: &mut impl FnMut(&mut Device<L>) -> Result<u16, Error>,
) -> Result<Observation, Error>
where
    O: Cia402Objects,
    L: Link,
    O::SafeTorqueOffWord: Readable<L::Protocol>,
{
    let statusword = statusword(device)?;
    let safe_torque_off = match O::SAFE_TORQUE_OFF_BIT {
        None => false,
        Some(bit) => (device.read_raw::<O::SafeTorqueOffWord>()? >> bit) & 1 == 1,
    };
    Ok(Observation {
        statusword,
        safe_torque_off,
        now: clock.now(),
    })
}

/// The state a CiA 402 drive is in now (`None`: the statusword shows no CiA 402 state).
pub fn state<O, L>(device: &mut Device<L>) -> Result<Option<State>, Error>
where
    O: Cia402Objects,
    L: Link,
    O::Statusword: Readable<L::Protocol>,
{
    Ok(State::decode(device.read_raw::<O::Statusword>()?))
}

/// Quick stop: from operation enabled to quick stop active (a drive whose quick stop option code
/// ends in switch on disabled counts as stopped there too); from any other state, disables.
pub fn quick_stop<O, L>(device: &mut Device<L>, deadline: Instant) -> Result<(), ControlError>
where
    O: Cia402Objects,
    L: Link,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::Statusword: Readable<L::Protocol>,
    O::SafeTorqueOffWord: Readable<L::Protocol>,
{
    if state::<O, L>(device)? != Some(State::OperationEnabled) {
        return drive_to::<O, L>(device, Target::SwitchOnDisabled, deadline);
    }
    match drive_to::<O, L>(device, Target::QuickStopActive, deadline) {
        Err(ControlError::Stuck {
            reason: StuckReason::Blocked(Blocker::QuickStopOnlyFromOperationEnabled),
            state: Some(name),
            ..
        }) if name == State::SwitchOnDisabled.name() => Ok(()),
        other => other,
    }
}

/// Fault reset: from fault (or fault reaction active) to switch on disabled; nothing to do otherwise.
pub fn fault_reset<O, L>(device: &mut Device<L>, deadline: Instant) -> Result<(), ControlError>
where
    O: Cia402Objects,
    L: Link,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::Statusword: Readable<L::Protocol>,
    O::SafeTorqueOffWord: Readable<L::Protocol>,
{
    match state::<O, L>(device)? {
        Some(State::Fault | State::FaultReactionActive) => {
            drive_to::<O, L>(device, Target::SwitchOnDisabled, deadline)
        }
        _ => Ok(()),
    }
}

/// Requests `mode` (0x6060) and waits until the mode display (0x6061) confirms it.
pub fn set_mode<O, L>(
    device: &mut Device<L>,
    mode: O::Mode,
    deadline: Instant,
) -> Result<(), ControlError>
where
    O: Cia402Modes,
    L: Link,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::ModesOfOperation: Writable<L::Protocol>,
    O::ModesOfOperationDisplay: Readable<L::Protocol>,
{
    let controlword = device.read_raw::<O::Controlword>()?;
    if let ModeStep::ClearHaltFirst { controlword } = mode::mode_change(&O::QUIRKS, controlword) {
        device.write_raw::<O::Controlword>(controlword)?;
    }
    device.write::<O::ModesOfOperation>(mode)?;
    let requested = mode.raw();
    loop {
        let displayed = device.read_raw::<O::ModesOfOperationDisplay>()?;
        if mode::confirmed(requested, displayed) {
            return Ok(());
        }
        if Instant::now() >= deadline {
            return Err(ControlError::ModeNotConfirmed {
                requested,
                displayed,
            });
        }
        thread::sleep(POLL_INTERVAL);
    }
}

/// Brings a drive with a vendor state machine to the state called `target`.
pub fn goto_state<V, L>(
    device: &mut Device<L>,
    target: &'static str,
    deadline: Instant,
) -> Result<(), ControlError>
where
    V: VendorMachine,
    L: Link,
    V::Status: Readable<L::Protocol>,
    V::Command: Writable<L::Protocol>,
{
    let machine = V::MACHINE;
    let goal = machine
        .state_index(target)
        .ok_or(ControlError::UnknownState(target))?;
    let mut commander = Commander { last: None };
    loop {
        let status = device.read_raw::<V::Status>()?;
        let current = machine.recognise(status);
        let stuck = |reason| ControlError::Stuck {
            target,
            state: current
                .and_then(|i| machine.states.get(usize::from(i)))
                .map(|s| s.name),
            status,
            reason,
        };
        let reason = match current.map(|from| machine.next(from, goal, |_| true)) {
            None => StuckReason::UnknownStatus,
            Some(Plan::Done) => return Ok(()),
            Some(Plan::Command(transition)) => {
                let TransitionKind::Command(command) = transition.kind else {
                    return Err(stuck(StuckReason::Unreachable));
                };
                if commander.should_write(command, status) {
                    device.write_raw::<V::Command>(command)?;
                }
                StuckReason::NoResponse {
                    transition,
                    command,
                }
            }
            Some(Plan::Await(transition)) => StuckReason::Awaiting(transition),
            Some(Plan::NeedsExternal(transition)) => {
                return Err(stuck(StuckReason::NeedsExternal(transition)))
            }
            Some(Plan::Unreachable | Plan::BadTable) => {
                return Err(stuck(StuckReason::Unreachable))
            }
        };
        if Instant::now() >= deadline {
            return Err(stuck(reason));
        }
        thread::sleep(POLL_INTERVAL);
    }
}

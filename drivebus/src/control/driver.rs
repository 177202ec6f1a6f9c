//! The blocking driver: walks a drive to a state by polling its status and writing commands until
//! the planner is done or the deadline passes, and says where and why it got stuck.

use std::thread;

/// The deadline type of the driver (re-exported so generated crates need no `std` import).
pub use std::time::Instant;

pub use super::control_error::{ControlError, StuckReason};
pub use super::walk::POLL_INTERVAL;

use super::cia402::{Observation, State, Target};
use super::mode::{self, ModeStep};
use super::objects::{Cia402Objects, VendorMachine};
use super::objects_on::{ModeOn, QuickStopOptionOn, WalkOn};
use super::stop_option::QuickStopEnd;
use super::walk::{self, Cia402Steps, Cia402Walk, MachineWalk, QuickStopWalk, Walk};
use super::Millis;
use crate::device::Device;
use crate::error::Error;
use crate::link::Link;
use crate::parameter::{OpenEnum, Readable, Writable};

/// Milliseconds since the driver started, the time the pure core sees.
struct Clock(Instant);

impl Clock {
    fn now(&self) -> Millis {
        Millis(u64::try_from(self.0.elapsed().as_millis()).unwrap_or(u64::MAX))
    }
}

/// Brings a CiA 402 drive to `target`, polling the statusword until `deadline`.
pub fn drive_to<O, L>(
    device: &mut Device<L>,
    target: Target,
    deadline: Instant,
) -> Result<(), ControlError>
where
    O: WalkOn<L::Protocol>,
    L: Link,
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
    statusword: impl FnMut(&mut Device<L>) -> Result<u16, Error>,
) -> Result<(), ControlError>
where
    O: Cia402Objects,
    L: Link,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::SafeTorqueOffWord: Readable<L::Protocol>,
{
    let start = |controlword, now| Cia402Walk::new(O::QUIRKS, target, controlword, now);
    run_walk::<O, L, _>(device, deadline, statusword, start, |_, _| {})
}

/// Runs the walk `start` makes from the controlword read and the time, polling the statusword
/// `statusword` gives until the walk ends or `deadline` passes. `after_write` runs right after
/// each command has gone out: where a walk learns what it needs only then (the quick stop's end).
fn run_walk<O, L, W>(
    device: &mut Device<L>,
    deadline: Instant,
    mut statusword: impl FnMut(&mut Device<L>) -> Result<u16, Error>,
    start: impl FnOnce(u16, Millis) -> W,
    mut after_write: impl FnMut(&mut Device<L>, &mut W),
) -> Result<(), ControlError>
where
    O: Cia402Objects,
    L: Link,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::SafeTorqueOffWord: Readable<L::Protocol>,
    W: Cia402Steps,
{
    let clock = Clock(Instant::now());
    let controlword = device.read_raw::<O::Controlword>()?;
    let mut walk = start(controlword, clock.now());
    loop {
        let seen = observe::<O, L>(device, &clock, &mut statusword)?;
        let (write, if_late) = match walk.step(&seen) {
            Walk::Done => return Ok(()),
            Walk::Failed(error) => return Err(error),
            Walk::Pending { write, if_late } => (write, if_late),
        };
        if let Some(controlword) = write {
            device.write_raw::<O::Controlword>(controlword)?;
            walk.sent(controlword, clock.now());
            after_write(device, &mut walk);
        }
        if Instant::now() >= deadline {
            return Err(if_late);
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
    O: WalkOn<L::Protocol>,
    L: Link,
{
    let target = walk::quick_stop_target(state::<O, L>(device)?);
    walk::quick_stop_outcome(drive_to::<O, L>(device, target, deadline))
}

/// Quick stop seen through to `end`, the end the drive's quick stop option code (605Ah) gives
/// ([`QuickStopEnd::of_code`]): from operation enabled the quick stop command, then, for codes
/// 0-4, the wait (no write) until the drive has braked and taken transition 12 to switch on
/// disabled; from any other state, disables. A drive that ends elsewhere than `end` fails with
/// [`ControlError::Stuck`].
pub fn quick_stop_to<O, L>(
    device: &mut Device<L>,
    end: QuickStopEnd,
    deadline: Instant,
) -> Result<(), ControlError>
where
    O: Cia402Objects,
    L: Link,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::Statusword: Readable<L::Protocol>,
    O::SafeTorqueOffWord: Readable<L::Protocol>,
{
    quick_stop_walk::<O, L>(device, end, deadline, |_, _| {})
}

/// [`quick_stop_to`], running `after_write` after each command the walk writes.
fn quick_stop_walk<O, L>(
    device: &mut Device<L>,
    end: QuickStopEnd,
    deadline: Instant,
    after_write: impl FnMut(&mut Device<L>, &mut QuickStopWalk),
) -> Result<(), ControlError>
where
    O: WalkOn<L::Protocol>,
    L: Link,
{
    let state = state::<O, L>(device)?;
    let statusword = |device: &mut Device<L>| device.read_raw::<O::Statusword>();
    let start = |controlword, now| QuickStopWalk::new(O::QUIRKS, end, state, controlword, now);
    run_walk::<O, L, _>(device, deadline, statusword, start, after_write)
}

/// Quick stop seen through to the end the drive's own quick stop option code (605Ah) gives, as
/// [`quick_stop_to`]. The order: the statusword (its state decides the command) and the
/// controlword (the command keeps its other bits) are read, the quick stop command goes out,
/// and only then is 605Ah read, once, to know what to wait for: a slow or failed read of the
/// code never holds the stop back. A failed read takes either end ([`QuickStopEnd::of_read`]);
/// no read starts once `deadline` has passed (one under way ends with the bus's own timeout).
pub fn quick_stop_by_option_code<O, L>(
    device: &mut Device<L>,
    deadline: Instant,
) -> Result<(), ControlError>
where
    O: QuickStopOptionOn<L::Protocol>,
    L: Link,
{
    // The end is open (either) until the command has gone out; then the code narrows it.
    let open = QuickStopEnd::of_read(None);
    quick_stop_walk::<O, L>(device, open, deadline, |device, walk| {
        if walk.wants_end() && Instant::now() < deadline {
            let code = device.read_raw::<O::QuickStopOptionCode>().ok();
            walk.narrow(QuickStopEnd::of_read(code));
        }
    })
}

/// Fault reset: from fault (or fault reaction active) to switch on disabled; nothing to do otherwise.
pub fn fault_reset<O, L>(device: &mut Device<L>, deadline: Instant) -> Result<(), ControlError>
where
    O: WalkOn<L::Protocol>,
    L: Link,
{
    if walk::needs_fault_reset(state::<O, L>(device)?) {
        drive_to::<O, L>(device, Target::SwitchOnDisabled, deadline)
    } else {
        Ok(())
    }
}

/// Requests `mode` (0x6060) and waits until the mode display (0x6061) confirms it.
pub fn set_mode<O, L>(
    device: &mut Device<L>,
    mode: O::Mode,
    deadline: Instant,
) -> Result<(), ControlError>
where
    O: ModeOn<L::Protocol>,
    L: Link,
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
    let mut walk = MachineWalk::new(V::MACHINE, target)?;
    loop {
        let status = device.read_raw::<V::Status>()?;
        let (write, if_late) = match walk.step(status) {
            Walk::Done => return Ok(()),
            Walk::Failed(error) => return Err(error),
            Walk::Pending { write, if_late } => (write, if_late),
        };
        if let Some(command) = write {
            device.write_raw::<V::Command>(command)?;
        }
        if Instant::now() >= deadline {
            return Err(if_late);
        }
        thread::sleep(POLL_INTERVAL);
    }
}

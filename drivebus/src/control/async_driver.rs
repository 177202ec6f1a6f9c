//! The async driver (feature `async`): walks a drive to a state over an async link, as the
//! blocking `driver` does, with the same steps ([`walk`]) and the same errors.
//!
//! Only the waiting differs. Nothing here reads a clock: the poll interval is slept on the
//! application's [`Timer`], and the whole procedure runs [`within`] its time limit, so the deadline
//! is the timer's own. A walk that runs out of time ends with the error its last step named (the
//! state it was stuck in and why), as the blocking driver's does; the request in flight at that
//! moment is dropped, which every [`AsyncLink`] leaves the bus consistent after.
//!
//! The planner's time (the fault reset bit's hold) is the sum of the poll intervals slept: it
//! leaves out the time the requests took, so a hold lasts at least as long as the drive needs,
//! never shorter.

use core::time::Duration;

use super::cia402::{Observation, State, Target};
use super::control_error::ControlError;
use super::mode::{self, ModeStep};
use super::objects::{Cia402Objects, VendorMachine};
use super::objects_on::{ModeOn, QuickStopOptionOn, WalkOn};
use super::stop_option::QuickStopEnd;
use super::walk::{self, Cia402Steps, Cia402Walk, MachineWalk, QuickStopWalk, Walk, POLL_INTERVAL};
use super::Millis;
use crate::asynch::{within, Async, AsyncLink, Elapsed, Timer};
use crate::device::Device;
use crate::error::{BusError, Error};
use crate::parameter::{OpenEnum, Parameter, Readable, Writable};

/// The planner's time: the poll intervals slept since the walk started.
struct SleptClock(Millis);

impl SleptClock {
    fn now(&self) -> Millis {
        self.0
    }

    /// Sleeps one poll interval on `timer`.
    async fn pause(&mut self, timer: &impl Timer) {
        timer.sleep(POLL_INTERVAL).await;
        let slept = u64::try_from(POLL_INTERVAL.as_millis()).unwrap_or(u64::MAX);
        self.0 = Millis(self.0 .0.saturating_add(slept));
    }
}

/// The error of a procedure whose time ran out before its first read (of `parameter`) was answered.
fn no_answer(parameter: &'static str) -> ControlError {
    ControlError::Bus(Error::Bus {
        parameter,
        cause: BusError::Timeout,
    })
}

/// The outcome of a procedure run [`within`] its limit: when the time ran out, the error `late`
/// held then (the one the procedure's last step named).
fn in_time(
    outcome: Result<Result<(), ControlError>, Elapsed>,
    late: ControlError,
) -> Result<(), ControlError> {
    outcome.unwrap_or(Err(late))
}

/// Brings a CiA 402 drive to `target`, polling the statusword for at most `limit`.
pub async fn drive_to<O, L>(
    device: &mut Device<Async<L>>,
    target: Target,
    timer: &impl Timer,
    limit: Duration,
) -> Result<(), ControlError>
where
    O: WalkOn<L::Protocol>,
    L: AsyncLink,
{
    let mut late = no_answer(O::Controlword::NAME);
    let start = |controlword, now| Cia402Walk::new(O::QUIRKS, target, controlword, now);
    let walk = walk_cia402::<O, L, _>(device, timer, &mut late, start, async |_, _| {});
    let outcome = within(timer, limit, walk).await;
    in_time(outcome, late)
}

/// Quick stop seen through to `end`, as the blocking driver's `quick_stop_to`: from operation
/// enabled the quick stop command, then, where `end` is switch on disabled, the wait (no write)
/// for the drive's own transition 12; from any other state, disables.
pub async fn quick_stop_to<O, L>(
    device: &mut Device<Async<L>>,
    end: QuickStopEnd,
    timer: &impl Timer,
    limit: Duration,
) -> Result<(), ControlError>
where
    O: WalkOn<L::Protocol>,
    L: AsyncLink,
{
    quick_stop_walk::<O, L>(device, end, timer, limit, async |_, _| {}).await
}

/// [`quick_stop_to`], awaiting `after_write` after each command the walk writes, all within
/// `limit`.
async fn quick_stop_walk<O, L>(
    device: &mut Device<Async<L>>,
    end: QuickStopEnd,
    timer: &impl Timer,
    limit: Duration,
    after_write: impl AsyncFnMut(&mut Device<Async<L>>, &mut QuickStopWalk),
) -> Result<(), ControlError>
where
    O: WalkOn<L::Protocol>,
    L: AsyncLink,
{
    let mut late = no_answer(O::Controlword::NAME);
    let procedure = async {
        let state = state::<O, L>(device).await?;
        let start = |controlword, now| QuickStopWalk::new(O::QUIRKS, end, state, controlword, now);
        walk_cia402::<O, L, _>(device, timer, &mut late, start, after_write).await
    };
    let outcome = within(timer, limit, procedure).await;
    in_time(outcome, late)
}

/// Quick stop seen through to the end the drive's own quick stop option code (605Ah) gives, as
/// the blocking driver's `quick_stop_by_option_code`, in the same order: the statusword (its
/// state decides the command) and the controlword (the command keeps its other bits) are read,
/// the quick stop command goes out, and only then is 605Ah read, once, to know what to wait
/// for: a slow or failed read of the code never holds the stop back (a failed one takes either
/// end). Everything, the read of the code included, runs within `limit`.
pub async fn quick_stop_by_option_code<O, L>(
    device: &mut Device<Async<L>>,
    timer: &impl Timer,
    limit: Duration,
) -> Result<(), ControlError>
where
    O: QuickStopOptionOn<L::Protocol>,
    L: AsyncLink,
{
    // The end is open (either) until the command has gone out; then the code narrows it.
    let open = QuickStopEnd::of_read(None);
    let narrow = async |device: &mut Device<Async<L>>, walk: &mut QuickStopWalk| {
        if walk.wants_end() {
            let code = device.read_raw::<O::QuickStopOptionCode>().await.ok();
            walk.narrow(QuickStopEnd::of_read(code));
        }
    };
    quick_stop_walk::<O, L>(device, open, timer, limit, narrow).await
}

/// The walk `start` makes from the controlword read and the time, recording in `late` the error
/// a deadline would end it with. `after_write` runs right after each command has gone out:
/// where a walk learns what it needs only then (the quick stop's end).
async fn walk_cia402<O, L, W>(
    device: &mut Device<Async<L>>,
    timer: &impl Timer,
    late: &mut ControlError,
    start: impl FnOnce(u16, Millis) -> W,
    mut after_write: impl AsyncFnMut(&mut Device<Async<L>>, &mut W),
) -> Result<(), ControlError>
where
    O: Cia402Objects,
    L: AsyncLink,
    O::Controlword: Readable<L::Protocol> + Writable<L::Protocol>,
    O::Statusword: Readable<L::Protocol>,
    O::SafeTorqueOffWord: Readable<L::Protocol>,
    W: Cia402Steps,
{
    let mut clock = SleptClock(Millis(0));
    let controlword = device.read_raw::<O::Controlword>().await?;
    let mut walk = start(controlword, clock.now());
    loop {
        let seen = observe::<O, L>(device, clock.now()).await?;
        let write = match walk.step(&seen) {
            Walk::Done => return Ok(()),
            Walk::Failed(error) => return Err(error),
            Walk::Pending { write, if_late } => {
                *late = if_late;
                write
            }
        };
        if let Some(controlword) = write {
            device.write_raw::<O::Controlword>(controlword).await?;
            walk.sent(controlword, clock.now());
            after_write(device, &mut walk).await;
        }
        clock.pause(timer).await;
    }
}

/// The statusword and, where the drive has one, the safe torque off bit, as seen at `now`.
async fn observe<O, L>(device: &mut Device<Async<L>>, now: Millis) -> Result<Observation, Error>
where
    O: WalkOn<L::Protocol>,
    L: AsyncLink,
{
    let statusword = device.read_raw::<O::Statusword>().await?;
    let safe_torque_off = match O::SAFE_TORQUE_OFF_BIT {
        None => false,
        Some(bit) => (device.read_raw::<O::SafeTorqueOffWord>().await? >> bit) & 1 == 1,
    };
    Ok(Observation {
        statusword,
        safe_torque_off,
        now,
    })
}

/// The state a CiA 402 drive is in now (`None`: the statusword shows no CiA 402 state).
pub async fn state<O, L>(device: &mut Device<Async<L>>) -> Result<Option<State>, Error>
where
    O: Cia402Objects,
    L: AsyncLink,
    O::Statusword: Readable<L::Protocol>,
{
    Ok(State::decode(device.read_raw::<O::Statusword>().await?))
}

/// Quick stop, as the blocking driver's: from operation enabled to quick stop active (or switch
/// on disabled, where the drive's quick stop ends); from any other state, disables.
pub async fn quick_stop<O, L>(
    device: &mut Device<Async<L>>,
    timer: &impl Timer,
    limit: Duration,
) -> Result<(), ControlError>
where
    O: WalkOn<L::Protocol>,
    L: AsyncLink,
{
    let target = walk::quick_stop_target(state::<O, L>(device).await?);
    walk::quick_stop_outcome(drive_to::<O, L>(device, target, timer, limit).await)
}

/// Fault reset: from fault (or fault reaction active) to switch on disabled; nothing to do
/// otherwise.
pub async fn fault_reset<O, L>(
    device: &mut Device<Async<L>>,
    timer: &impl Timer,
    limit: Duration,
) -> Result<(), ControlError>
where
    O: WalkOn<L::Protocol>,
    L: AsyncLink,
{
    if walk::needs_fault_reset(state::<O, L>(device).await?) {
        drive_to::<O, L>(device, Target::SwitchOnDisabled, timer, limit).await
    } else {
        Ok(())
    }
}

/// Requests `mode` (0x6060) and waits, for at most `limit`, until the mode display (0x6061)
/// confirms it.
pub async fn set_mode<O, L>(
    device: &mut Device<Async<L>>,
    mode: O::Mode,
    timer: &impl Timer,
    limit: Duration,
) -> Result<(), ControlError>
where
    O: ModeOn<L::Protocol>,
    L: AsyncLink,
{
    let mut late = no_answer(O::Controlword::NAME);
    let procedure = async {
        let controlword = device.read_raw::<O::Controlword>().await?;
        if let ModeStep::ClearHaltFirst { controlword } = mode::mode_change(&O::QUIRKS, controlword)
        {
            device.write_raw::<O::Controlword>(controlword).await?;
        }
        device.write::<O::ModesOfOperation>(mode).await?;
        let requested = mode.raw();
        loop {
            let displayed = device.read_raw::<O::ModesOfOperationDisplay>().await?;
            if mode::confirmed(requested, displayed) {
                return Ok(());
            }
            late = ControlError::ModeNotConfirmed {
                requested,
                displayed,
            };
            timer.sleep(POLL_INTERVAL).await;
        }
    };
    let outcome = within(timer, limit, procedure).await;
    in_time(outcome, late)
}

/// Brings a drive with a vendor state machine to the state called `target`, for at most `limit`.
pub async fn goto_state<V, L>(
    device: &mut Device<Async<L>>,
    target: &'static str,
    timer: &impl Timer,
    limit: Duration,
) -> Result<(), ControlError>
where
    V: VendorMachine,
    L: AsyncLink,
    V::Status: Readable<L::Protocol>,
    V::Command: Writable<L::Protocol>,
{
    let mut walk = MachineWalk::new(V::MACHINE, target)?;
    let mut late = no_answer(V::Status::NAME);
    let procedure = async {
        loop {
            let status = device.read_raw::<V::Status>().await?;
            let write = match walk.step(status) {
                Walk::Done => return Ok(()),
                Walk::Failed(error) => return Err(error),
                Walk::Pending { write, if_late } => {
                    late = if_late;
                    write
                }
            };
            if let Some(command) = write {
                device.write_raw::<V::Command>(command).await?;
            }
            timer.sleep(POLL_INTERVAL).await;
        }
    };
    let outcome = within(timer, limit, procedure).await;
    in_time(outcome, late)
}

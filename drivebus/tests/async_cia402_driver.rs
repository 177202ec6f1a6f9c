//! The async CiA 402 driver against our device double, with a timer that counts polls instead of
//! reading a clock: the same walks, commands and errors as the blocking driver's, deterministic.
#![cfg(all(feature = "canopen", feature = "async"))]

use core::future::{poll_fn, Future};
use core::pin::pin;
use core::task::{Context, Poll, Waker};
use std::cell::Cell;
use std::time::{Duration, Instant};

use drivebus::asynch::{Alarm, Async, Timer};
use drivebus::canopen::{CanOpenLink, NodeId, SdoBus};
use drivebus::control::device::Cia402Device;
use drivebus::control::driver;
use drivebus::control::walk::POLL_INTERVAL;
use drivebus::control::{async_driver, ControlError, State, StuckReason, Target, Waiting};
use drivebus::testing::{Immediate, LinkRequest, MemoryBus, Recorded};
use drivebus::{BusError, Device, VariantId};

#[path = "support/cia402_objects.rs"]
mod objects;

use objects::{HaltQuirk, Mode, Objects, Standard};

/// A CiA 402 drive behind SDO: 0x6040 moves the double, 0x6041 reads its statusword (frozen:
/// the controlword is kept but the state never moves); anything else is memory.
struct Drive {
    double: Cia402Device,
    frozen: bool,
    memory: MemoryBus,
}

impl Drive {
    fn in_state(state: State) -> Self {
        let mut memory = MemoryBus::new();
        memory
            .set_object(0x2003, 0, &[0, 0])
            .set_object(0x6040, 0, &[0, 0])
            .set_object(0x6060, 0, &[0])
            .set_object(0x6061, 0, &[0]);
        Self {
            double: Cia402Device::in_state(state),
            frozen: false,
            memory,
        }
    }
}

impl SdoBus for Drive {
    fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        sub: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        let word = match index {
            0x6040 => self.double.controlword(),
            0x6041 => self.double.statusword(),
            _ => return self.memory.upload(node, index, sub, out),
        };
        out[..2].copy_from_slice(&word.to_le_bytes());
        Ok(2)
    }

    fn download(&mut self, node: NodeId, index: u16, sub: u8, data: &[u8]) -> Result<(), BusError> {
        if index != 0x6040 {
            return self.memory.download(node, index, sub, data);
        }
        let controlword = u16::from_le_bytes([data[0], data[1]]);
        if self.frozen {
            self.memory.download(node, index, sub, data)
        } else {
            self.double.write_controlword(controlword);
            self.double.tick();
            Ok(())
        }
    }
}

type Link = Recorded<CanOpenLink<Drive>, drivebus::canopen::ObjectAddress>;

fn blocking(drive: Drive) -> Device<Link> {
    Device::new(
        Recorded::new(CanOpenLink::new(drive, NodeId(5))),
        VariantId::default(),
    )
}

fn awaited(drive: Drive) -> Device<Async<Immediate<Link>>> {
    let link = Recorded::new(CanOpenLink::new(drive, NodeId(5)));
    Device::new(Async(Immediate(link)), VariantId::default())
}

fn log_of(
    device: &mut Device<Async<Immediate<Link>>>,
) -> Vec<LinkRequest<drivebus::canopen::ObjectAddress>> {
    device.link_mut().0 .0.log_without_repeats()
}

/// A timer over poll counts: a poll interval passes at the next poll of the task; any longer
/// sleep (a procedure's limit) ends once `limit` poll intervals have been slept.
struct Polls {
    slept: Cell<u32>,
    limit: u32,
}

impl Polls {
    fn allowing(limit: u32) -> Self {
        Self {
            slept: Cell::new(0),
            limit,
        }
    }
}

/// The alarm of [`Polls`]: never due (the procedures here keep no alarm; only clients do).
struct NeverDue;

impl Alarm for NeverDue {
    fn set(&mut self, _: Duration) {}

    fn poll_due(&mut self, _: &mut Context<'_>) -> Poll<()> {
        Poll::Pending
    }
}

impl Timer for Polls {
    type Alarm = NeverDue;

    fn alarm(&self) -> NeverDue {
        NeverDue
    }

    async fn sleep(&self, duration: Duration) {
        if duration == POLL_INTERVAL {
            self.slept.set(self.slept.get() + 1);
            let mut yielded = false;
            poll_fn(|cx| {
                if yielded {
                    return Poll::Ready(());
                }
                yielded = true;
                cx.waker().wake_by_ref();
                Poll::Pending
            })
            .await;
        } else {
            poll_fn(|_| {
                if self.slept.get() >= self.limit {
                    Poll::Ready(())
                } else {
                    Poll::Pending
                }
            })
            .await;
        }
    }
}

/// Polls `future` to completion (its every wait ends at a later poll); fails past 100,000 polls.
fn run<F: Future>(future: F) -> F::Output {
    let mut future = pin!(future);
    let mut cx = Context::from_waker(Waker::noop());
    for _ in 0..100_000 {
        if let Poll::Ready(output) = future.as_mut().poll(&mut cx) {
            return output;
        }
    }
    panic!("the future never completed");
}

const LIMIT: Duration = Duration::from_secs(1);

fn soon() -> Instant {
    Instant::now() + LIMIT
}

#[test]
fn the_async_walk_sends_the_blocking_walk_s_requests() {
    for target in Target::ALL {
        for start in [
            State::SwitchOnDisabled,
            State::OperationEnabled,
            State::Fault,
        ] {
            let mut sync = blocking(Drive::in_state(start));
            let sync_outcome = driver::drive_to::<Standard, _>(&mut sync, target, soon());
            let mut async_ = awaited(Drive::in_state(start));
            let timer = Polls::allowing(100);
            let async_outcome = run(async_driver::drive_to::<Standard, _>(
                &mut async_,
                target,
                &timer,
                LIMIT,
            ));
            assert_eq!(async_outcome, sync_outcome, "{start} to {target:?}");
            assert_eq!(
                log_of(&mut async_),
                sync.link_mut().log_without_repeats(),
                "{start} to {target:?}"
            );
        }
    }
}

#[test]
fn out_of_time_the_walk_says_which_transition_the_drive_did_not_take() {
    let mut drive = Drive::in_state(State::SwitchOnDisabled);
    drive.frozen = true;
    let mut device = awaited(drive);
    let timer = Polls::allowing(5);
    let error = run(async_driver::drive_to::<Standard, _>(
        &mut device,
        Target::OperationEnabled,
        &timer,
        LIMIT,
    ))
    .unwrap_err();
    assert!(
        matches!(error, ControlError::Stuck { reason: StuckReason::NoResponse { transition, command: 0x0006 }, .. } if transition.name == "2"),
        "{error}"
    );
    // The shutdown command went out once, not once per poll.
    let writes = device
        .link_mut()
        .0
         .0
        .log()
        .iter()
        .filter(|r| matches!(r, LinkRequest::Write(..)))
        .count();
    assert_eq!(writes, 1);
}

#[test]
fn the_planner_s_time_is_the_poll_intervals_slept() {
    // A drive that stays in fault, a hold of 3 ms: bit 7 raised at 0 ms, still held after the
    // second poll interval, when the limit of two intervals ends the walk.
    let mut drive = Drive::in_state(State::Fault);
    drive.frozen = true;
    let mut device = awaited(drive);
    let error = run(async_driver::fault_reset::<Objects<3, false>, _>(
        &mut device,
        &Polls::allowing(2),
        LIMIT,
    ))
    .unwrap_err();
    assert!(
        matches!(
            error,
            ControlError::Stuck {
                reason: StuckReason::Waiting(Waiting::FaultResetHold { remaining_ms: 2 }),
                ..
            }
        ),
        "{error}"
    );
    // A drive that takes the reset: back in switch on disabled.
    let mut device = awaited(Drive::in_state(State::Fault));
    let timer = Polls::allowing(100);
    run(async_driver::fault_reset::<Standard, _>(
        &mut device,
        &timer,
        LIMIT,
    ))
    .unwrap();
    assert_eq!(
        run(async_driver::state::<Standard, _>(&mut device)),
        Ok(Some(State::SwitchOnDisabled))
    );
}

#[test]
fn an_unconfirmed_mode_names_both_modes_and_halt_is_cleared_where_the_drive_needs_it() {
    let mut device = awaited(Drive::in_state(State::OperationEnabled));
    let timer = Polls::allowing(3);
    let error = run(async_driver::set_mode::<Standard, _>(
        &mut device,
        Mode(-3),
        &timer,
        LIMIT,
    ));
    assert_eq!(
        error,
        Err(ControlError::ModeNotConfirmed {
            requested: -3,
            displayed: 0
        })
    );
    let mut sync = blocking(Drive::in_state(State::OperationEnabled));
    let sync_outcome = driver::set_mode::<HaltQuirk, _>(&mut sync, Mode(0), soon());
    let mut async_ = awaited(Drive::in_state(State::OperationEnabled));
    let outcome = run(async_driver::set_mode::<HaltQuirk, _>(
        &mut async_,
        Mode(0),
        &Polls::allowing(3),
        LIMIT,
    ));
    assert_eq!((outcome, sync_outcome), (Ok(()), Ok(())));
    assert_eq!(log_of(&mut async_), sync.link_mut().log_without_repeats());
}

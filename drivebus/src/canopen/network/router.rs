//! The blocking router: a thread that owns the bus, sends what the core queued, routes what
//! arrives and runs the timers (SYNC, heartbeat deadlines).
//!
//! [`CanBus`] has one `&mut self` for sending and receiving, so the thread cannot be woken out
//! of a receive to send: it receives for at most one poll interval at a time, and a frame a
//! caller queued waits at most that long on a silent bus (a received frame ends the wait at
//! once, so a busy bus sends sooner). While SDO transfers are in flight the interval is
//! [`BUSY_POLL_INTERVAL`], so the next request of a transfer, or of a caller that just finished
//! one, goes out soon; an idle network wakes only every poll interval.

use core::time::Duration;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use super::shared::Shared;
use crate::canopen::can::CanBus;
use crate::error::BusError;

/// How long the router receives at a time while SDO transfers are in flight, and for 20 ms
/// after the last one ended.
pub const BUSY_POLL_INTERVAL: Duration = Duration::from_micros(100);

/// How long the router stays quick after a transfer ended: a caller that reads one object after
/// another starts its next transfer within that time, and should not wait a whole poll
/// interval for it to go out.
const LINGER: Duration = Duration::from_millis(20);

/// Most frames received in one go before the queued frames are sent again, so a flooded bus
/// cannot starve the senders.
const BURST: usize = 64;

/// Runs the router on `bus` until `stop` is set or the bus fails; gives the bus back.
pub(crate) fn run<B: CanBus>(
    mut bus: B,
    shared: &Shared,
    stop: &Arc<AtomicBool>,
    poll_interval: Duration,
) -> (B, Result<(), BusError>) {
    let mut result = Ok(());
    let mut busy_until = Duration::ZERO;
    while !stop.load(Ordering::Acquire) {
        if let Err(error) = turn(&mut bus, shared, poll_interval, &mut busy_until) {
            result = Err(error);
            break;
        }
    }
    let mut state = shared.lock();
    state.ended = Some(match &result {
        Err(error) => error.clone(),
        Ok(()) => BusError::Closed,
    });
    drop(state);
    shared.wake_all();
    (bus, result)
}

/// One turn: send what is queued, run the timers, receive for at most `poll_interval` (or until
/// the next timer; [`BUSY_POLL_INTERVAL`] until `busy_until`), route what came.
fn turn<B: CanBus>(
    bus: &mut B,
    shared: &Shared,
    poll_interval: Duration,
    busy_until: &mut Duration,
) -> Result<(), BusError> {
    send_queued(bus, shared)?;
    let wait = {
        let mut state = shared.lock();
        let now = shared.now();
        if state.core.handle_time(now) {
            shared.wake_all();
        }
        if state.core.has_transmit() {
            return Ok(());
        }
        if state.core.transfers_in_flight() {
            *busy_until = now + LINGER;
        }
        let interval = if now < *busy_until {
            poll_interval.min(BUSY_POLL_INTERVAL)
        } else {
            poll_interval
        };
        state
            .core
            .next_deadline()
            .map_or(interval, |d| d.saturating_sub(now).min(interval))
    };
    for turn in 0..BURST {
        let Some(frame) = bus.recv(if turn == 0 { wait } else { Duration::ZERO })? else {
            break;
        };
        let touched = shared.lock().core.handle(&frame, shared.now());
        if let Some(node) = touched {
            shared.wake(node);
        }
    }
    Ok(())
}

fn send_queued<B: CanBus>(bus: &mut B, shared: &Shared) -> Result<(), BusError> {
    loop {
        let Some(frame) = shared.lock().core.poll_transmit() else {
            return Ok(());
        };
        bus.send(&frame)?;
    }
}

//! The async router: a future that owns the bus, sends what the core queued, routes what
//! arrives and runs the timers. Unlike the blocking router it is woken the moment a frame is
//! queued: the bus's `recv` is cancel-safe, so it is raced against the queue and the timers.

use core::future::{poll_fn, Future};
use core::pin::pin;
use core::task::Poll;
use core::time::Duration;
use std::sync::Arc;

use super::shared::{wake, Shared};
use crate::asynch::Timer;
use crate::canopen::can::AsyncCanBus;
use crate::canopen::frame::CanFrame;
use crate::error::BusError;

/// Longest sleep with no timer due: a safety net, nothing depends on it.
const IDLE: Duration = Duration::from_secs(1);

/// Drives an [`AsyncNetwork`](super::AsyncNetwork): poll [`run`](Self::run) alongside the
/// application (spawn it, or join it with the work).
#[derive(Debug)]
pub struct AsyncRouter<B, T> {
    bus: B,
    timer: T,
    shared: Arc<Shared>,
}

/// What ended a wait of the router.
enum Woken {
    Frame(Result<CanFrame, BusError>),
    Queued,
    Timer,
}

impl<B: AsyncCanBus, T: Timer> AsyncRouter<B, T> {
    pub(crate) fn new(bus: B, timer: T, shared: Arc<Shared>) -> Self {
        Self { bus, timer, shared }
    }

    /// Routes until the network is closed ([`AsyncNetwork::close`](super::AsyncNetwork::close),
    /// `Ok`) or the bus fails (its error). Every waiting handle is then answered with
    /// [`BusError::Closed`] or that error.
    pub async fn run(&mut self) -> Result<(), BusError> {
        let result = self.serve().await;
        let wakers = {
            let mut state = self.shared.lock();
            state.ended = Some(result.clone().err().unwrap_or(BusError::Closed));
            state.take_all()
        };
        wake(wakers);
        result
    }

    /// Gives the bus back.
    pub fn into_inner(self) -> B {
        self.bus
    }

    async fn serve(&mut self) -> Result<(), BusError> {
        loop {
            self.send_queued().await?;
            let now = self.shared.now();
            let (wait, planned) = {
                let mut state = self.shared.lock();
                if state.closing {
                    return Ok(());
                }
                if state.core.handle_time(now) {
                    let wakers = state.take_all();
                    drop(state);
                    wake(wakers);
                    continue;
                }
                let planned = state.core.next_deadline();
                let wait = planned.map_or(IDLE, |d| d.saturating_sub(now).min(IDLE));
                (wait, planned)
            };
            match self.wait(wait, planned).await {
                Woken::Frame(frame) => self.route(&frame?),
                Woken::Queued | Woken::Timer => {}
            }
        }
    }

    async fn send_queued(&mut self) -> Result<(), BusError> {
        loop {
            let Some(frame) = self.shared.lock().core.poll_transmit() else {
                return Ok(());
            };
            self.bus.send(&frame).await?;
        }
    }

    fn route(&self, frame: &CanFrame) {
        let wakers = {
            let mut state = self.shared.lock();
            match state.core.handle(frame, self.shared.now()) {
                Some(node) => state.take_node(node),
                None => return,
            }
        };
        wake(wakers);
    }

    /// Waits for a frame, a frame queued to send (or a close), a timer set meanwhile that is
    /// due before the `planned` one (SYNC started, a heartbeat monitored), or `wait` to pass.
    async fn wait(&mut self, wait: Duration, planned: Option<Duration>) -> Woken {
        let shared = &self.shared;
        let mut recv = pin!(self.bus.recv());
        let mut sleep = pin!(self.timer.sleep(wait));
        poll_fn(|cx| {
            if let Poll::Ready(frame) = recv.as_mut().poll(cx) {
                return Poll::Ready(Woken::Frame(frame));
            }
            {
                let mut state = shared.lock();
                if state.core.has_transmit() || state.closing {
                    return Poll::Ready(Woken::Queued);
                }
                // A handle's update woke the router: its new timer must not wait out the old sleep.
                if earlier(state.core.next_deadline(), planned) {
                    return Poll::Ready(Woken::Timer);
                }
                state.router_waits(cx);
            }
            sleep.as_mut().poll(cx).map(|()| Woken::Timer)
        })
        .await
    }
}

/// Whether the timer due `next` comes before the `planned` one the router sleeps until.
fn earlier(next: Option<Duration>, planned: Option<Duration>) -> bool {
    match (next, planned) {
        (Some(next), Some(planned)) => next < planned,
        (Some(_), None) => true,
        (None, _) => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_timer_set_meanwhile_ends_the_sleep_only_when_due_earlier() {
        let ms = Duration::from_millis;
        assert!(earlier(Some(ms(1)), None), "SYNC started while idle");
        assert!(earlier(Some(ms(1)), Some(ms(5))));
        assert!(!earlier(Some(ms(5)), Some(ms(5))), "the timer slept for");
        assert!(!earlier(None, Some(ms(5))));
    }
}

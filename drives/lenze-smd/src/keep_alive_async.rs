//! The watchdog keep-alive on the async handle (drivebus's `async`, with `std`): what
//! [`KeepAlive`](crate::KeepAlive)'s thread does, as steps an async task takes. An async handle
//! is owned by one task at a time, so there is no thread to hand it to: [`AsyncKeepAlive::poll`]
//! reads the status block once and records it, for a task that shares the handle (behind its
//! runtime's mutex) and sleeps [`AsyncKeepAlive::interval`] between polls;
//! [`AsyncKeepAlive::run`] is that loop for a task that owns the handle, until dropped.
//!
//! The deadline bookkeeping is the thread's own (`Watch`). The time it sees is the caller's: the
//! `now` given to `poll`, or in `run` the intervals slept (the requests' own time left out, so
//! a silence shows as a little shorter than it was).

use core::time::Duration;

use drivebus::asynch::{Async, AsyncLink, Timer};
use drivebus::modbus::Modbus;

use crate::keep_alive::{KeepAliveReport, Watch};
use crate::{KeepAlive, LenzeSmd};

/// The keep-alive of an async handle: its report, and the deadline bookkeeping.
pub struct AsyncKeepAlive {
    watch: Watch,
    interval: Duration,
    report: KeepAliveReport,
}

impl core::fmt::Debug for AsyncKeepAlive {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("AsyncKeepAlive")
            .field("interval", &self.interval)
            .field("report", &self.report)
            .finish_non_exhaustive()
    }
}

impl AsyncKeepAlive {
    /// A keep-alive for a watchdog `timeout` (see `watchdog_timeout_async`), polling at a third
    /// of it, started now.
    pub fn new(timeout: Duration) -> Self {
        Self {
            watch: Watch::new(timeout),
            interval: KeepAlive::interval_for(timeout),
            report: KeepAliveReport::default(),
        }
    }

    /// How often the drive should be polled.
    pub fn interval(&self) -> Duration {
        self.interval
    }

    /// What happened so far.
    pub fn report(&self) -> &KeepAliveReport {
        &self.report
    }

    /// Reads the status block once and records the outcome at `now` (time since
    /// [`Self::new`]).
    pub async fn poll<L: AsyncLink<Protocol = Modbus>>(
        &mut self,
        drive: &mut LenzeSmd<Async<L>>,
        now: Duration,
    ) {
        let poll = drive.status_async().await.map(|_| ());
        self.watch.record(poll, now, &mut self.report);
    }

    /// Polls `drive` every [`Self::interval`] of `timer`'s time; never completes: drop the
    /// future (select it against the application's work, or abort its task) to stop.
    pub async fn run<L: AsyncLink<Protocol = Modbus>>(
        &mut self,
        drive: &mut LenzeSmd<Async<L>>,
        timer: &impl Timer,
    ) {
        let mut now = Duration::ZERO;
        loop {
            timer.sleep(self.interval).await;
            now = now.saturating_add(self.interval);
            self.poll(drive, now).await;
        }
    }
}

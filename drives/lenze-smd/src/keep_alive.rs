//! The watchdog keep-alive (section 4.4, lines 370-387): once unlocked, with n22 not 0, the drive
//! acts (inhibit, quick stop or trip FC3) when it hears nothing valid for n23 ms, and the master
//! should communicate "at less than 1/2 the interval" (line 372). [`KeepAlive`] reads the status
//! block (#24, 6 registers, as 4.8 step 8 suggests, line 445) from a thread every third of the
//! timeout, stops when dropped, and records every time the drive went unanswered longer than
//! the timeout.

use std::sync::mpsc::{self, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};
use std::vec::Vec;

use drivebus::modbus::{ModbusLink, RegisterBus};
use drivebus::Error;

use crate::LenzeSmd;

/// Polls per timeout: three, so the interval stays under the manual's half.
const POLLS_PER_TIMEOUT: u32 = 3;

/// A time the drive went without a successful poll for longer than its timeout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MissedDeadline {
    /// From the last successful poll to the moment the miss was noticed.
    pub silent_for: Duration,
}

/// What the keep-alive has done so far.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct KeepAliveReport {
    /// Successful polls.
    pub polls: u64,
    /// Each stretch without an answer longer than the timeout, once per stretch.
    pub missed: Vec<MissedDeadline>,
    /// The last failed poll's error.
    pub last_error: Option<Error>,
}

/// A thread that keeps the drive's watchdog fed; stops when dropped.
#[derive(Debug)]
pub struct KeepAlive {
    stop: Option<Sender<()>>,
    thread: Option<JoinHandle<()>>,
    report: Arc<Mutex<KeepAliveReport>>,
    interval: Duration,
}

impl KeepAlive {
    /// The poll interval for a watchdog `timeout`: a third of it.
    pub fn interval_for(timeout: Duration) -> Duration {
        timeout / POLLS_PER_TIMEOUT
    }

    /// Reads n22 and n23 (the generated [`LenzeSmd::watchdog_timeout`] of the description's
    /// `[watchdog]`) and starts polling at a third of n23; `None` (nothing started) while n22
    /// says the watchdog is not active.
    pub fn for_drive<B: RegisterBus + Send + 'static>(
        drive: Arc<Mutex<LenzeSmd<ModbusLink<B>>>>,
    ) -> Result<Option<Self>, Error> {
        let timeout = drive
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .watchdog_timeout()?;
        Ok(timeout.map(|timeout| Self::spawn(drive, timeout)))
    }

    /// Starts polling `drive` for a watchdog `timeout` (see [`LenzeSmd::watchdog_timeout`]).
    pub fn spawn<B: RegisterBus + Send + 'static>(
        drive: Arc<Mutex<LenzeSmd<ModbusLink<B>>>>,
        timeout: Duration,
    ) -> Self {
        let (stop, stopped) = mpsc::channel::<()>();
        let report = Arc::new(Mutex::new(KeepAliveReport::default()));
        let interval = Self::interval_for(timeout);
        let shared = Arc::clone(&report);
        let thread = std::thread::spawn(move || {
            let started = Instant::now();
            let mut watch = Watch::new(timeout);
            while let Err(RecvTimeoutError::Timeout) = stopped.recv_timeout(interval) {
                let poll = drive
                    .lock()
                    .unwrap_or_else(PoisonError::into_inner)
                    .status()
                    .map(|_| ());
                let mut report = shared.lock().unwrap_or_else(PoisonError::into_inner);
                watch.record(poll, started.elapsed(), &mut report);
            }
        });
        Self {
            stop: Some(stop),
            thread: Some(thread),
            report,
            interval,
        }
    }

    /// How often the drive is polled.
    pub fn interval(&self) -> Duration {
        self.interval
    }

    /// A copy of what happened so far.
    pub fn report(&self) -> KeepAliveReport {
        self.report
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone()
    }
}

impl Drop for KeepAlive {
    fn drop(&mut self) {
        drop(self.stop.take());
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// Deadline bookkeeping of a keep-alive, the thread's and the async one's: the time is what the
/// caller measures from the keep-alive's start.
pub(crate) struct Watch {
    timeout: Duration,
    last_answer: Duration,
    miss_reported: bool,
}

impl Watch {
    /// A watch started at time zero, for a watchdog `timeout`.
    pub(crate) fn new(timeout: Duration) -> Self {
        Self {
            timeout,
            last_answer: Duration::ZERO,
            miss_reported: false,
        }
    }

    /// Records the outcome of a poll that ended at `now`.
    pub(crate) fn record(
        &mut self,
        poll: Result<(), Error>,
        now: Duration,
        report: &mut KeepAliveReport,
    ) {
        let silent_for = now.saturating_sub(self.last_answer);
        if silent_for > self.timeout && !self.miss_reported {
            report.missed.push(MissedDeadline { silent_for });
            self.miss_reported = true;
        }
        match poll {
            Ok(()) => {
                report.polls += 1;
                self.last_answer = now;
                self.miss_reported = false;
            }
            Err(error) => report.last_error = Some(error),
        }
    }
}

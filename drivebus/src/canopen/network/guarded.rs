//! The one lock and the one clock of a network manager, shared by its router and its handles.

use core::time::Duration;
use std::sync::{Mutex, MutexGuard};
use std::time::Instant;

/// A shell's state behind a mutex, and the manager's clock.
#[derive(Debug)]
pub(crate) struct Guarded<S> {
    state: Mutex<S>,
    epoch: Instant,
}

impl<S> Guarded<S> {
    pub(crate) fn new(state: S) -> Self {
        Self {
            state: Mutex::new(state),
            epoch: Instant::now(),
        }
    }

    /// The manager's clock: time since the network was made.
    pub(crate) fn now(&self) -> Duration {
        self.epoch.elapsed()
    }

    /// Locks the state; a thread that panicked holding it left it consistent (every update
    /// is one call on the core), so a poisoned lock is used as it is.
    pub(crate) fn lock(&self) -> MutexGuard<'_, S> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }
}

//! The state the blocking router thread and the callers' threads share: the core behind one
//! mutex, one condition variable per node (so a frame for node 5 wakes node 5's waiters only,
//! not all 32 threads), and how the router ended, if it did.

use core::ops::Deref;
use core::time::Duration;
use std::sync::{Condvar, MutexGuard};
use std::vec::Vec;

use super::core::NetworkCore;
use super::guarded::Guarded;
use crate::canopen::address::NodeId;
use crate::error::BusError;

/// The core and what the router reports, behind one lock.
#[derive(Debug)]
pub(crate) struct State {
    pub(crate) core: NetworkCore,
    /// Set when the router stopped: the bus failed, or the network was shut down.
    pub(crate) ended: Option<BusError>,
}

#[derive(Debug)]
pub(crate) struct Shared {
    guarded: Guarded<State>,
    /// One per node id (0..=127); waiters on a node wait on its own.
    changed: Vec<Condvar>,
}

impl Deref for Shared {
    type Target = Guarded<State>;

    fn deref(&self) -> &Guarded<State> {
        &self.guarded
    }
}

impl Shared {
    pub(crate) fn new() -> Self {
        Self {
            guarded: Guarded::new(State {
                core: NetworkCore::new(),
                ended: None,
            }),
            changed: (0..=NodeId::MAX).map(|_| Condvar::new()).collect(),
        }
    }

    /// Runs `update` on the state (the router sends what it queued within a poll interval).
    pub(crate) fn update<R>(&self, update: impl FnOnce(&mut State) -> R) -> R {
        update(&mut self.lock())
    }

    fn condvar(&self, node: NodeId) -> &Condvar {
        &self.changed[usize::from(node.get()).min(self.changed.len() - 1)]
    }

    /// Wakes the threads waiting on `node`.
    pub(crate) fn wake(&self, node: NodeId) {
        self.condvar(node).notify_all();
    }

    /// Wakes every waiting thread (timers fired, the router ended).
    pub(crate) fn wake_all(&self) {
        self.changed.iter().for_each(Condvar::notify_all);
    }

    /// Waits at most `timeout` for news about `node`, releasing the lock meanwhile.
    pub(crate) fn wait<'a>(
        &'a self,
        guard: MutexGuard<'a, State>,
        node: NodeId,
        timeout: Duration,
    ) -> MutexGuard<'a, State> {
        match self.condvar(node).wait_timeout(guard, timeout) {
            Ok((guard, _)) => guard,
            Err(poisoned) => poisoned.into_inner().0,
        }
    }
}

//! The state the async router and the node futures share: the core behind one mutex, and the
//! wakers of whoever waits (per node, and the router's).

use core::task::{Context, Waker};
use std::vec::Vec;

use crate::canopen::address::NodeId;
use crate::canopen::network::guarded::Guarded;
use crate::canopen::network::NetworkCore;
use crate::error::BusError;

#[derive(Debug)]
pub(crate) struct State {
    pub(crate) core: NetworkCore,
    /// Set when the router stopped: the bus failed, or the network was closed.
    pub(crate) ended: Option<BusError>,
    /// [`AsyncNetwork::close`](super::AsyncNetwork::close) was called.
    pub(crate) closing: bool,
    waiters: Vec<Vec<Waker>>,
    router: Option<Waker>,
}

impl State {
    /// Remembers `cx`'s waker as waiting on `node`.
    pub(crate) fn wait_on(&mut self, node: NodeId, cx: &Context<'_>) {
        let slot = usize::from(node.get()).min(self.waiters.len() - 1);
        let wakers = &mut self.waiters[slot];
        if !wakers.iter().any(|w| w.will_wake(cx.waker())) {
            wakers.push(cx.waker().clone());
        }
    }

    /// Remembers `cx`'s waker as the router's.
    pub(crate) fn router_waits(&mut self, cx: &Context<'_>) {
        self.router = Some(cx.waker().clone());
    }

    /// Takes the wakers of `node`'s waiters.
    pub(crate) fn take_node(&mut self, node: NodeId) -> Vec<Waker> {
        let slot = usize::from(node.get()).min(self.waiters.len() - 1);
        core::mem::take(&mut self.waiters[slot])
    }

    /// Takes every waiter's waker.
    pub(crate) fn take_all(&mut self) -> Vec<Waker> {
        self.waiters.iter_mut().flat_map(core::mem::take).collect()
    }

    /// Takes the router's waker.
    pub(crate) fn take_router(&mut self) -> Option<Waker> {
        self.router.take()
    }
}

/// The async shell's state and clock; its waiters live in the state, under the same lock.
pub(crate) type Shared = Guarded<State>;

impl Guarded<State> {
    pub(crate) fn new_async() -> Self {
        Self::new(State {
            core: NetworkCore::new(),
            ended: None,
            closing: false,
            waiters: (0..=NodeId::MAX).map(|_| Vec::new()).collect(),
            router: None,
        })
    }

    /// Runs `update` on the state, then wakes the router so it sends what was queued. Wakers
    /// are woken after the lock is released.
    pub(crate) fn update<R>(&self, update: impl FnOnce(&mut State) -> R) -> R {
        let (result, router) = {
            let mut state = self.lock();
            let result = update(&mut state);
            (result, state.take_router())
        };
        if let Some(router) = router {
            router.wake();
        }
        result
    }
}

/// Wakes every waker in `wakers`.
pub(crate) fn wake(wakers: impl IntoIterator<Item = Waker>) {
    wakers.into_iter().for_each(Waker::wake);
}

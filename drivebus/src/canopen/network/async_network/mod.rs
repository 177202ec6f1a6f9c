//! The async network manager: the same core as the blocking [`Network`](super::Network), with
//! a router future in place of the router thread. Runtime-agnostic: any [`AsyncCanBus`] and
//! any [`Timer`]; the application polls [`AsyncRouter::run`] beside its own work (spawn it, or
//! join it), and [`AsyncNetwork::close`] ends it.
//!
//! ```no_run
//! # async fn demo() -> Result<(), drivebus::BusError> {
//! use drivebus::asynch::TokioTimer;
//! use drivebus::canopen::can::async_in_process::AsyncInProcessBus;
//! use drivebus::canopen::network::AsyncNetwork;
//! use drivebus::canopen::{AsyncSdoBus, NodeId};
//!
//! let bus = AsyncInProcessBus::new();
//! let (network, mut router) = AsyncNetwork::new(bus.endpoint(), TokioTimer);
//! let work = async {
//!     let mut reads = Vec::new();
//!     for id in 1..=8u8 {
//!         let mut sdo = network.node(NodeId(id));
//!         reads.push(async move {
//!             let mut out = [0u8; 4];
//!             sdo.upload(NodeId(id), 0x1000, 0, &mut out).await.map(|_| out)
//!         });
//!     }
//!     // ... await them together (join_all, a JoinSet, select) ...
//!     network.close();
//! };
//! let (routed, ()) = tokio::join!(router.run(), work);
//! routed
//! # }
//! ```

mod node_sdo;
mod router;
mod shared;
mod subscription;

use core::time::Duration;
use std::sync::Arc;

pub use node_sdo::AsyncNodeSdo;
pub use router::AsyncRouter;
use shared::{wake, Shared};
pub use subscription::AsyncSubscription;

use crate::asynch::Timer;
use crate::canopen::address::NodeId;
use crate::canopen::can::AsyncCanBus;
use crate::error::BusError;

/// A handle on an async network manager: make node handles and subscribers, send NMT, set
/// SYNC and heartbeat monitoring. Cloning it shares the same network.
#[derive(Debug, Clone)]
pub struct AsyncNetwork<T> {
    shared: Arc<Shared>,
    timer: T,
}

impl<T: Timer + Clone> AsyncNetwork<T> {
    /// A manager on `bus`, timed by `timer`: the handle, and the router to poll.
    pub fn new<B: AsyncCanBus>(bus: B, timer: T) -> (Self, AsyncRouter<B, T>) {
        let shared = Arc::new(Shared::new_async());
        let router = AsyncRouter::new(bus, timer.clone(), Arc::clone(&shared));
        (Self { shared, timer }, router)
    }

    /// An SDO client for `node` ([`AsyncSdoBus`](crate::canopen::AsyncSdoBus)) sharing this
    /// network's bus. Transfers to different nodes run at once; a second transfer to the same
    /// node waits for the first.
    pub fn node(&self, node: NodeId) -> AsyncNodeSdo<T> {
        AsyncNodeSdo::new(Arc::clone(&self.shared), self.timer.clone(), node)
    }

    /// The timer the network waits on (the cyclic shell's feedback time limits).
    pub(crate) fn timer(&self) -> &T {
        &self.timer
    }
}

impl<T> AsyncNetwork<T> {
    /// Subscribes to `node`'s events in a queue of `capacity`; when it is full the oldest
    /// event is dropped and counted, the router never waits. One subscriber per node.
    pub fn subscribe(&self, node: NodeId, capacity: usize) -> AsyncSubscription {
        AsyncSubscription::new(Arc::clone(&self.shared), node, capacity)
    }

    super::manager_methods::manager_methods!();

    /// Ends the router once it has sent what is queued; handles then answer
    /// [`BusError::Closed`].
    pub fn close(&self) {
        let wakers = self.shared.update(|state| {
            state.closing = true;
            state.take_all()
        });
        wake(wakers);
    }
}

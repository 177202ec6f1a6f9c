//! The blocking network manager: a router thread owns the bus; [`NodeSdo`] handles and
//! [`Subscription`]s on any thread share it through the core.

use core::time::Duration;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;

use super::node_sdo::NodeSdo;
use super::shared::Shared;
use super::subscription::Subscription;
use crate::canopen::address::NodeId;
use crate::canopen::can::CanBus;
use crate::error::BusError;

/// How long the router receives at a time by default, and so the longest a frame queued on a
/// silent bus waits to be sent.
pub const DEFAULT_POLL_INTERVAL: Duration = Duration::from_millis(1);

/// What the router thread ends with: the bus, and why it stopped.
type Ended<B> = (B, Result<(), BusError>);
type Router<B> = JoinHandle<Ended<B>>;

/// A CANopen network manager owning one CAN bus: SDO clients for many nodes at once
/// ([`node`](Self::node)), per-node event subscribers ([`subscribe`](Self::subscribe)), NMT,
/// a SYNC producer and a heartbeat consumer.
///
/// A router thread owns the bus. Dropping the network (or [`shutdown`](Self::shutdown)) stops
/// it; handles still around then answer [`BusError::Closed`].
#[derive(Debug)]
pub struct Network<B> {
    shared: Arc<Shared>,
    stop: Arc<AtomicBool>,
    router: Option<Router<B>>,
}

impl<B: CanBus + Send + 'static> Network<B> {
    /// Starts a manager on `bus` with [`DEFAULT_POLL_INTERVAL`].
    pub fn new(bus: B) -> Self {
        Self::with_poll_interval(bus, DEFAULT_POLL_INTERVAL)
    }

    /// Starts a manager on `bus` whose router receives for at most `poll_interval` at a time:
    /// shorter sends sooner on a silent bus, longer wakes less often.
    pub fn with_poll_interval(bus: B, poll_interval: Duration) -> Self {
        let shared = Arc::new(Shared::new());
        let stop = Arc::new(AtomicBool::new(false));
        let router = {
            let (shared, stop) = (Arc::clone(&shared), Arc::clone(&stop));
            let interval = poll_interval.max(Duration::from_micros(50));
            std::thread::Builder::new()
                .name("canopen-network".into())
                .spawn(move || super::router::run(bus, &shared, &stop, interval))
        };
        let router = match router {
            Ok(router) => Some(router),
            Err(error) => {
                shared.lock().ended = Some(BusError::Io(error.kind()));
                None
            }
        };
        Self {
            shared,
            stop,
            router,
        }
    }
}

impl<B> Network<B> {
    /// An SDO client for `node` ([`SdoBus`](crate::canopen::SdoBus)) sharing this network's
    /// bus: wrap it in a [`CanOpenLink`](crate::canopen::CanOpenLink) (or hand it to a
    /// generated drive's constructor) and use it from any thread. Transfers to different nodes
    /// run at once; a second transfer to the same node waits for the first.
    pub fn node(&self, node: NodeId) -> NodeSdo {
        NodeSdo::new(Arc::clone(&self.shared), node)
    }

    /// Subscribes to `node`'s PDOs, EMCYs, boot-ups, state changes and heartbeat losses, kept
    /// in a queue of `capacity` events; when it is full the oldest event is dropped and counted
    /// ([`Subscription::dropped`]), the router never waits. One subscriber per node: a new one
    /// replaces the earlier one's queue.
    pub fn subscribe(&self, node: NodeId, capacity: usize) -> Subscription {
        Subscription::new(Arc::clone(&self.shared), node, capacity)
    }

    super::manager_methods::manager_methods!();

    /// Stops the router and gives the bus back, or the error the bus failed with.
    pub fn shutdown(mut self) -> Result<B, BusError> {
        self.stop_router()
            .unwrap_or(Err(BusError::Closed))
            .and_then(|(bus, result)| result.map(|()| bus))
    }

    fn stop_router(&mut self) -> Option<Result<Ended<B>, BusError>> {
        self.stop.store(true, Ordering::Release);
        let router = self.router.take()?;
        // A router that panicked has no bus to give back.
        Some(router.join().map_err(|_| BusError::Closed))
    }
}

impl<B> Drop for Network<B> {
    fn drop(&mut self) {
        drop(self.stop_router());
    }
}

//! A blocking subscriber to one node's events.

use core::time::Duration;
use std::sync::Arc;
use std::time::Instant;

use super::event::NetworkEvent;
use super::shared::Shared;
use crate::canopen::address::NodeId;
use crate::canopen::network::core::SubscriptionId;
use crate::error::BusError;

/// One node's events, from [`Network::subscribe`](super::Network::subscribe); dropping it
/// unsubscribes.
#[derive(Debug)]
pub struct Subscription {
    shared: Arc<Shared>,
    id: SubscriptionId,
}

impl Subscription {
    pub(crate) fn new(shared: Arc<Shared>, node: NodeId, capacity: usize) -> Self {
        let id = shared.lock().core.subscribe(node, capacity);
        Self { shared, id }
    }

    /// The node.
    pub fn node(&self) -> NodeId {
        self.id.node()
    }

    /// The oldest event, without waiting.
    pub fn try_recv(&self) -> Option<NetworkEvent> {
        self.shared.lock().core.next_event(self.id.node())
    }

    /// The oldest event, waiting at most `timeout` for one: `Ok(None)` when none came, an
    /// error once the network stopped and every kept event was taken.
    pub fn recv(&self, timeout: Duration) -> Result<Option<NetworkEvent>, BusError> {
        let deadline = Instant::now() + timeout;
        let mut state = self.shared.lock();
        loop {
            if let Some(event) = state.core.next_event(self.id.node()) {
                return Ok(Some(event));
            }
            if let Some(error) = &state.ended {
                return Err(error.clone());
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Ok(None);
            }
            state = self.shared.wait(state, self.id.node(), left);
        }
    }

    /// Events dropped because the queue was full.
    pub fn dropped(&self) -> u64 {
        self.shared.lock().core.dropped_events(self.id.node())
    }
}

impl Drop for Subscription {
    fn drop(&mut self) {
        self.shared.lock().core.unsubscribe(self.id);
    }
}

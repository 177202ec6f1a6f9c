//! An async subscriber to one node's events.

use core::future::poll_fn;
use core::task::Poll;
use std::sync::Arc;

use super::shared::Shared;
use crate::canopen::address::NodeId;
use crate::canopen::network::core::SubscriptionId;
use crate::canopen::network::NetworkEvent;
use crate::error::BusError;

/// One node's events, from [`AsyncNetwork::subscribe`](super::AsyncNetwork::subscribe);
/// dropping it unsubscribes.
#[derive(Debug)]
pub struct AsyncSubscription {
    shared: Arc<Shared>,
    id: SubscriptionId,
}

impl AsyncSubscription {
    pub(crate) fn new(shared: Arc<Shared>, node: NodeId, capacity: usize) -> Self {
        let id = shared.lock().core.subscribe(node, capacity);
        Self { shared, id }
    }

    /// The node.
    pub fn node(&self) -> NodeId {
        self.id.node()
    }

    /// The oldest event, without waiting.
    pub fn try_next(&self) -> Option<NetworkEvent> {
        self.shared.lock().core.next_event(self.id.node())
    }

    /// The oldest event, waiting for one; an error once the network stopped and every kept
    /// event was taken. Cancel-safe: a dropped future took no event.
    pub async fn next(&self) -> Result<NetworkEvent, BusError> {
        poll_fn(|cx| {
            let mut state = self.shared.lock();
            if let Some(event) = state.core.next_event(self.id.node()) {
                return Poll::Ready(Ok(event));
            }
            if let Some(error) = &state.ended {
                return Poll::Ready(Err(error.clone()));
            }
            state.wait_on(self.id.node(), cx);
            Poll::Pending
        })
        .await
    }

    /// Events dropped because the queue was full.
    pub fn dropped(&self) -> u64 {
        self.shared.lock().core.dropped_events(self.id.node())
    }
}

impl Drop for AsyncSubscription {
    fn drop(&mut self) {
        self.shared.lock().core.unsubscribe(self.id);
    }
}

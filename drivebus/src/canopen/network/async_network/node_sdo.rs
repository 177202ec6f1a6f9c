//! An async SDO client for one node of an [`AsyncNetwork`](super::AsyncNetwork): the sans-I/O
//! transfer runs in the caller's future, fed the responses the router sorted into the node's
//! inbox. Dropping the future mid-transfer queues the SDO abort, as
//! [`AsyncSdo`](crate::canopen::async_client::AsyncSdo) sends it. Each handle keeps one alarm
//! for its transfers' deadlines, moved at each transfer, as `AsyncSdo` does.

use core::future::poll_fn;
use core::pin::pin;
use core::task::Poll;
use core::time::Duration;
use std::sync::Arc;

use super::shared::{wake, Shared};
use crate::asynch::alarm::Aimed;
use crate::asynch::race::{first, First};
use crate::asynch::Timer;
use crate::canopen::address::NodeId;
use crate::canopen::async_client::CANCEL_CODE;
use crate::canopen::client::backlog::{outcome, settings_methods, Settings};
use crate::canopen::client::DEFAULT_TIMEOUT;
use crate::canopen::frame::CanFrame;
use crate::canopen::link::AsyncSdoBus;
use crate::canopen::network::own_node::own_node;
use crate::canopen::sdo::{Progress, Transfer};
use crate::error::BusError;

/// An [`AsyncSdoBus`] for one node on a shared [`AsyncNetwork`](super::AsyncNetwork); transfers
/// to other nodes than its own are refused ([`BusError::Unsupported`]).
#[derive(Debug)]
pub struct AsyncNodeSdo<T: Timer> {
    shared: Arc<Shared>,
    timer: T,
    /// The transfers' deadline, kept from one transfer to the next and moved at each.
    alarm: T::Alarm,
    node: NodeId,
    settings: Settings,
}

/// A clone has an alarm of its own (a clone is another task's handle).
impl<T: Timer + Clone> Clone for AsyncNodeSdo<T> {
    fn clone(&self) -> Self {
        Self {
            shared: Arc::clone(&self.shared),
            alarm: self.timer.alarm(),
            timer: self.timer.clone(),
            node: self.node,
            settings: self.settings,
        }
    }
}

/// The node's channel, claimed: released on drop, after queueing the abort of a transfer
/// still in flight.
struct Claim<'a> {
    shared: &'a Shared,
    node: NodeId,
    abort: Option<CanFrame>,
}

impl Drop for Claim<'_> {
    fn drop(&mut self) {
        let abort = self.abort;
        let wakers = self.shared.update(|state| {
            if let Some(abort) = abort {
                // A full queue means a dead bus: the server times out on its own.
                let _ = state.core.transmit(abort);
            }
            state.core.release_sdo(self.node);
            state.take_node(self.node)
        });
        wake(wakers);
    }
}

impl<T: Timer> AsyncNodeSdo<T> {
    pub(crate) fn new(shared: Arc<Shared>, timer: T, node: NodeId) -> Self {
        Self {
            shared,
            alarm: timer.alarm(),
            timer,
            node,
            settings: Settings::new(DEFAULT_TIMEOUT),
        }
    }

    /// The node this handle talks to.
    pub fn node(&self) -> NodeId {
        self.node
    }

    settings_methods!();

    /// Claims the channel, starts the transfer `start` makes and drives it to its end.
    async fn run<X: Transfer>(
        &mut self,
        start: impl FnOnce(Duration) -> X,
    ) -> Result<usize, BusError> {
        let (shared, node, alarm) = (&*self.shared, self.node, &mut self.alarm);
        let mut claim = claim(shared, node).await?;
        let mut transfer = start(shared.now());
        let mut progress = Progress::Pending;
        let mut alarm = Aimed::new(alarm);
        loop {
            let queued = shared.update(|state| {
                // Queued after the end too: a failure may have queued an abort for the server.
                core::iter::from_fn(|| transfer.poll_transmit()).all(|f| state.core.transmit(f))
            });
            if !queued {
                return Err(BusError::CanQueueFull);
            }
            claim.abort = transfer.abort_frame(CANCEL_CODE);
            if let Some(result) = outcome(progress, &transfer) {
                claim.abort = None;
                return result;
            }
            let Some(deadline) = transfer.deadline() else {
                return Err(BusError::Frame("SDO transfer ended without a result"));
            };
            alarm.aim(deadline, shared.now());
            progress = match first(response(shared, node), pin!(alarm.due())).await {
                First::A(frame) => transfer.handle(&frame?, shared.now()),
                First::B(()) => transfer.handle_timeout(shared.now().max(deadline)),
            };
        }
    }
}

/// Waits until no other transfer to `node` is in flight, then claims its channel.
async fn claim(shared: &Shared, node: NodeId) -> Result<Claim<'_>, BusError> {
    poll_fn(|cx| {
        let mut state = shared.lock();
        if let Some(error) = &state.ended {
            return Poll::Ready(Err(error.clone()));
        }
        if state.core.claim_sdo(node) {
            return Poll::Ready(Ok(()));
        }
        state.wait_on(node, cx);
        Poll::Pending
    })
    .await?;
    Ok(Claim {
        shared,
        node,
        abort: None,
    })
}

/// The next response for `node`'s transfer.
async fn response(shared: &Shared, node: NodeId) -> Result<CanFrame, BusError> {
    poll_fn(|cx| {
        let mut state = shared.lock();
        if let Some(frame) = state.core.next_sdo_response(node) {
            return Poll::Ready(Ok(frame));
        }
        if let Some(error) = &state.ended {
            return Poll::Ready(Err(error.clone()));
        }
        state.wait_on(node, cx);
        Poll::Pending
    })
    .await
}

impl<T: Timer> AsyncSdoBus for AsyncNodeSdo<T> {
    async fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        own_node(self.node, node)?;
        let settings = self.settings;
        self.run(|now| settings.upload(node, (index, subindex), out, now))
            .await
    }

    async fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        own_node(self.node, node)?;
        let settings = self.settings;
        self.run(|now| settings.download(node, (index, subindex), data, now))
            .await
            .map(|_| ())
    }
}

//! An async SDO client for one node of an [`AsyncNetwork`](super::AsyncNetwork): the sans-I/O
//! transfer runs in the caller's future, fed the responses the router sorted into the node's
//! inbox. Dropping the future mid-transfer queues the SDO abort, as
//! [`AsyncSdo`](crate::canopen::async_client::AsyncSdo) sends it.

use core::future::poll_fn;
use core::pin::pin;
use core::task::Poll;
use core::time::Duration;
use std::sync::Arc;

use super::shared::{wake, Shared};
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
#[derive(Debug, Clone)]
pub struct AsyncNodeSdo<T> {
    shared: Arc<Shared>,
    timer: T,
    node: NodeId,
    settings: Settings,
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

    /// Waits until no other transfer to the node is in flight, then claims its channel.
    async fn claim(&self) -> Result<Claim<'_>, BusError> {
        poll_fn(|cx| {
            let mut state = self.shared.lock();
            if let Some(error) = &state.ended {
                return Poll::Ready(Err(error.clone()));
            }
            if state.core.claim_sdo(self.node) {
                return Poll::Ready(Ok(()));
            }
            state.wait_on(self.node, cx);
            Poll::Pending
        })
        .await?;
        Ok(Claim {
            shared: &self.shared,
            node: self.node,
            abort: None,
        })
    }

    /// The next response for the node's transfer.
    async fn response(&self) -> Result<CanFrame, BusError> {
        poll_fn(|cx| {
            let mut state = self.shared.lock();
            if let Some(frame) = state.core.next_sdo_response(self.node) {
                return Poll::Ready(Ok(frame));
            }
            if let Some(error) = &state.ended {
                return Poll::Ready(Err(error.clone()));
            }
            state.wait_on(self.node, cx);
            Poll::Pending
        })
        .await
    }

    /// Claims the channel, starts the transfer `start` makes and drives it to its end.
    async fn run<X: Transfer>(&self, start: impl FnOnce(Duration) -> X) -> Result<usize, BusError> {
        let mut claim = self.claim().await?;
        let mut transfer = start(self.shared.now());
        let mut progress = Progress::Pending;
        loop {
            let queued = self.shared.update(|state| {
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
            let left = deadline.saturating_sub(self.shared.now());
            let sleep = pin!(self.timer.sleep(left));
            progress = match first(self.response(), sleep).await {
                First::A(frame) => transfer.handle(&frame?, self.shared.now()),
                First::B(()) => transfer.handle_timeout(self.shared.now().max(deadline)),
            };
        }
    }
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

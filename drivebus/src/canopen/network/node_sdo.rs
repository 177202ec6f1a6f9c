//! A blocking SDO client for one node of a [`Network`](super::Network): the sans-I/O transfer
//! runs on the caller's thread, fed the responses the router sorted into the node's inbox.

use core::time::Duration;
use std::sync::{Arc, MutexGuard};

use super::own_node::own_node;
use super::shared::{Shared, State};
use crate::canopen::address::NodeId;
use crate::canopen::client::backlog::{outcome, settings_methods, Settings};
use crate::canopen::client::DEFAULT_TIMEOUT;
use crate::canopen::link::SdoBus;
use crate::canopen::sdo::{Progress, Transfer};
use crate::error::BusError;

/// An [`SdoBus`] for one node on a shared [`Network`](super::Network); `Send`, so each drive
/// can live on its own thread. Transfers to other nodes than its own are refused
/// ([`BusError::Unsupported`]): the handle's node is its channel.
#[derive(Debug, Clone)]
pub struct NodeSdo {
    shared: Arc<Shared>,
    node: NodeId,
    settings: Settings,
}

impl NodeSdo {
    pub(crate) fn new(shared: Arc<Shared>, node: NodeId) -> Self {
        Self {
            shared,
            node,
            settings: Settings::new(DEFAULT_TIMEOUT),
        }
    }

    /// The node this handle talks to.
    pub fn node(&self) -> NodeId {
        self.node
    }

    settings_methods!();

    /// Waits until no other transfer to the node is in flight, then claims the node's channel.
    fn claim(&self) -> Result<MutexGuard<'_, State>, BusError> {
        let mut state = self.shared.lock();
        loop {
            if let Some(error) = &state.ended {
                return Err(error.clone());
            }
            if state.core.claim_sdo(self.node) {
                return Ok(state);
            }
            state = self.shared.wait(state, self.node, self.settings.timeout);
        }
    }

    /// Claims the node's channel, starts the transfer `start` makes (its first deadline
    /// counts from then, not from the wait for the channel) and drives it to its end; the
    /// channel is released however it ends.
    fn run<T: Transfer>(&self, start: impl FnOnce(Duration) -> T) -> Result<usize, BusError> {
        let state = self.claim()?;
        let mut transfer = start(self.shared.now());
        let result = self.drive(state, &mut transfer);
        let mut state = self.shared.lock();
        state.core.release_sdo(self.node);
        drop(state);
        self.shared.wake(self.node);
        result
    }

    fn drive<'s, T: Transfer>(
        &'s self,
        mut state: MutexGuard<'s, State>,
        transfer: &mut T,
    ) -> Result<usize, BusError> {
        let mut progress = Progress::Pending;
        loop {
            // Queued after the end too: a failure may have queued an abort for the server.
            while let Some(frame) = transfer.poll_transmit() {
                if !state.core.transmit(frame) {
                    return Err(BusError::CanQueueFull);
                }
            }
            if let Some(result) = outcome(progress, transfer) {
                return result;
            }
            let Some(deadline) = transfer.deadline() else {
                return Err(BusError::Frame("SDO transfer ended without a result"));
            };
            progress = loop {
                if let Some(frame) = state.core.next_sdo_response(self.node) {
                    break transfer.handle(&frame, self.shared.now());
                }
                if let Some(error) = &state.ended {
                    return Err(error.clone());
                }
                let now = self.shared.now();
                if now >= deadline {
                    break transfer.handle_timeout(now);
                }
                state = self.shared.wait(state, self.node, deadline - now);
            };
        }
    }
}

impl SdoBus for NodeSdo {
    fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        own_node(self.node, node)?;
        let settings = self.settings;
        self.run(|now| settings.upload(node, (index, subindex), out, now))
    }

    fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        own_node(self.node, node)?;
        let settings = self.settings;
        self.run(|now| settings.download(node, (index, subindex), data, now))
            .map(|_| ())
    }
}

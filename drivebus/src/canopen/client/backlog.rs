//! The frames an SDO client keeps while its transfers run, and the settings it starts them
//! with: shared by the blocking [`BlockingSdo`](super::BlockingSdo) and the async
//! `AsyncSdo`, which differ only in how they wait.

use crate::canopen::address::NodeId;
use crate::canopen::bounded_queue::BoundedQueue;
use crate::canopen::frame::CanFrame;
use crate::canopen::sdo::{Download, Progress, SdoClient, Transfer, Upload};
use crate::error::BusError;
use core::time::Duration;

use super::BACKLOG;

/// Frames that arrived during transfers but were not theirs (PDOs, heartbeats, EMCY, other
/// nodes' SDOs), oldest first, at most [`BACKLOG`]; older ones are dropped first.
#[derive(Debug)]
pub(crate) struct Backlog {
    frames: BoundedQueue<CanFrame>,
}

impl Default for Backlog {
    fn default() -> Self {
        Self {
            frames: BoundedQueue::new(BACKLOG),
        }
    }
}

impl Backlog {
    /// Keeps `frame` for the bus's own receive.
    pub(crate) fn keep(&mut self, frame: CanFrame) {
        self.frames.push(frame);
    }

    /// The oldest kept frame.
    pub(crate) fn pop(&mut self) -> Option<CanFrame> {
        self.frames.pop()
    }

    /// Frames dropped because the backlog was full.
    pub(crate) fn dropped(&self) -> usize {
        usize::try_from(self.frames.dropped()).unwrap_or(usize::MAX)
    }

    /// A received frame, sorted: `Some` if it is on the transfer's response COB-ID
    /// `response_cob`, otherwise kept (and `None`).
    pub(crate) fn sort(&mut self, frame: CanFrame, response_cob: u16) -> Option<CanFrame> {
        if frame.id() == response_cob {
            Some(frame)
        } else {
            self.keep(frame);
            None
        }
    }
}

/// The end of a transfer after its frames were sent: its result, or `None` while it runs.
pub(crate) fn outcome<T: Transfer>(
    progress: Progress,
    transfer: &T,
) -> Option<Result<usize, BusError>> {
    let (index, subindex) = transfer.object();
    match progress {
        Progress::Done(len) => Some(Ok(len)),
        Progress::Failed(error) => Some(Err(error.into_bus_error(index, subindex))),
        Progress::Pending if transfer.deadline().is_none() => {
            Some(Err(BusError::Frame("SDO transfer ended without a result")))
        }
        Progress::Pending => None,
    }
}

/// How an SDO client starts its transfers: the time a server has to answer each request, and
/// from which size on block transfers are used.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Settings {
    pub(crate) timeout: Duration,
    pub(crate) block_threshold: Option<usize>,
    pub(crate) block_size: u8,
}

impl Settings {
    pub(crate) fn new(timeout: Duration) -> Self {
        Self {
            timeout,
            block_threshold: None,
            block_size: crate::canopen::sdo::block::MAX_BLOCK_SIZE,
        }
    }

    fn use_block(&self, len: usize) -> bool {
        self.block_threshold
            .is_some_and(|threshold| len >= threshold)
    }

    /// The upload of `node`'s `index:subindex` into `out`, started at `now`.
    pub(crate) fn upload<'a>(
        &self,
        node: NodeId,
        (index, subindex): (u16, u8),
        out: &'a mut [u8],
        now: Duration,
    ) -> Upload<'a> {
        let client = SdoClient::new(node, self.timeout);
        if self.use_block(out.len()) {
            client.block_upload(index, subindex, out, self.block_size, now)
        } else {
            client.upload(index, subindex, out, now)
        }
    }

    /// The download of `data` to `node`'s `index:subindex`, started at `now`.
    pub(crate) fn download<'a>(
        &self,
        node: NodeId,
        (index, subindex): (u16, u8),
        data: &'a [u8],
        now: Duration,
    ) -> Download<'a> {
        let client = SdoClient::new(node, self.timeout);
        if self.use_block(data.len()) {
            client.block_download(index, subindex, data, now)
        } else {
            client.download(index, subindex, data, now)
        }
    }
}

/// The builder methods of the SDO clients and the network's node handles, over their
/// `settings` field.
macro_rules! settings_methods {
    () => {
        /// Sets how long the server has to answer each request.
        pub fn with_timeout(mut self, timeout: Duration) -> Self {
            self.settings.timeout = timeout;
            self
        }

        /// Uses block transfers for values (downloads) or buffers (uploads) of at least
        /// `threshold` bytes, with `block_size` segments per block.
        pub fn with_block_transfers(mut self, threshold: usize, block_size: u8) -> Self {
            self.settings.block_threshold = Some(threshold);
            self.settings.block_size = block_size;
            self
        }
    };
}
pub(crate) use settings_methods;

/// The settings and accessors both SDO clients offer, over their `bus`, `settings` and
/// `backlog` fields.
macro_rules! client_methods {
    () => {
        $crate::canopen::client::backlog::settings_methods!();

        /// The underlying bus.
        pub fn bus_mut(&mut self) -> &mut B {
            &mut self.bus
        }

        /// Gives the bus back.
        pub fn into_inner(self) -> B {
            self.bus
        }

        /// Frames dropped because the backlog was full.
        pub fn dropped_frames(&self) -> usize {
            self.backlog.dropped()
        }
    };
}
pub(crate) use client_methods;

//! A blocking SDO client over any [`CanBus`]: the sans-I/O transfers driven with a real clock.

use core::time::Duration;
use std::collections::VecDeque;
use std::time::Instant;

use super::address::NodeId;
use super::backend::CanBus;
use super::frame::CanFrame;
use super::link::SdoBus;
use super::sdo::{Progress, SdoClient, Transfer};
use crate::error::BusError;

/// Most frames kept for [`CanBus::recv`] while transfers run; older ones are dropped first.
pub const BACKLOG: usize = 1024;

/// Default time a server has to answer each request.
pub const DEFAULT_TIMEOUT: Duration = Duration::from_millis(500);

/// Runs SDO transfers over a [`CanBus`]; implements [`SdoBus`], so a
/// [`CanOpenLink`](super::CanOpenLink) works over every backend.
///
/// Frames that arrive during a transfer but are not SDO responses for it (PDOs, heartbeats,
/// EMCY, other nodes' SDOs) are kept, up to [`BACKLOG`] of them, and handed out first by this
/// type's own [`CanBus::recv`], so one bus serves SDO and everything else.
#[derive(Debug)]
pub struct BlockingSdo<B> {
    bus: B,
    backlog: VecDeque<CanFrame>,
    dropped: usize,
    timeout: Duration,
    block_threshold: Option<usize>,
    block_size: u8,
    epoch: Instant,
}

impl<B: CanBus> BlockingSdo<B> {
    /// An SDO client on `bus` with [`DEFAULT_TIMEOUT`]; expedited and segmented transfers only.
    pub fn new(bus: B) -> Self {
        Self {
            bus,
            backlog: VecDeque::new(),
            dropped: 0,
            timeout: DEFAULT_TIMEOUT,
            block_threshold: None,
            block_size: super::sdo::block::MAX_BLOCK_SIZE,
            epoch: Instant::now(),
        }
    }

    /// Sets how long the server has to answer each request.
    pub fn with_timeout(mut self, timeout: Duration) -> Self {
        self.timeout = timeout;
        self
    }

    /// Uses block transfers for values (downloads) or buffers (uploads) of at least `threshold`
    /// bytes, with `block_size` segments per block.
    pub fn with_block_transfers(mut self, threshold: usize, block_size: u8) -> Self {
        self.block_threshold = Some(threshold);
        self.block_size = block_size;
        self
    }

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
        self.dropped
    }

    fn keep(&mut self, frame: CanFrame) {
        if self.backlog.len() == BACKLOG {
            self.backlog.pop_front();
            self.dropped += 1;
        }
        self.backlog.push_back(frame);
    }

    fn now(&self) -> Duration {
        self.epoch.elapsed()
    }

    fn client(&self, node: NodeId) -> SdoClient {
        SdoClient::new(node, self.timeout)
    }

    fn use_block(&self, len: usize) -> bool {
        self.block_threshold
            .is_some_and(|threshold| len >= threshold)
    }

    /// Drives `transfer` to its end: sends its frames, feeds it received frames and the time.
    pub fn run<T: Transfer>(&mut self, transfer: &mut T) -> Result<usize, BusError> {
        let mut progress = Progress::Pending;
        loop {
            // Drained after the end too: a failure may have queued an abort for the server.
            while let Some(frame) = transfer.poll_transmit() {
                self.bus.send(&frame)?;
            }
            let (index, subindex) = transfer.object();
            match progress {
                Progress::Done(len) => return Ok(len),
                Progress::Failed(error) => return Err(error.into_bus_error(index, subindex)),
                Progress::Pending => {}
            }
            let Some(deadline) = transfer.deadline() else {
                return Err(BusError::Frame("SDO transfer ended without a result"));
            };
            let now = self.now();
            progress = match self.bus.recv(deadline.saturating_sub(now))? {
                Some(frame) if frame.id() == transfer.response_cob() => {
                    transfer.handle(&frame, self.now())
                }
                Some(frame) => {
                    self.keep(frame);
                    Progress::Pending
                }
                None => transfer.handle_timeout(self.now()),
            };
        }
    }
}

impl<B: CanBus> SdoBus for BlockingSdo<B> {
    fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        let client = self.client(node);
        let now = self.now();
        let mut transfer = if self.use_block(out.len()) {
            client.block_upload(index, subindex, out, self.block_size, now)
        } else {
            client.upload(index, subindex, out, now)
        };
        self.run(&mut transfer)
    }

    fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        let client = self.client(node);
        let now = self.now();
        let mut transfer = if self.use_block(data.len()) {
            client.block_download(index, subindex, data, now)
        } else {
            client.download(index, subindex, data, now)
        };
        self.run(&mut transfer).map(|_| ())
    }
}

/// The bus beside the SDO client: frames that arrived during transfers come first.
impl<B: CanBus> CanBus for BlockingSdo<B> {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.bus.send(frame)
    }

    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        match self.backlog.pop_front() {
            Some(frame) => Ok(Some(frame)),
            None => self.bus.recv(timeout),
        }
    }
}

//! A blocking SDO client over any [`CanBus`]: the sans-I/O transfers driven with a real clock.

pub mod lss;
pub mod scan;

use core::time::Duration;
use std::collections::VecDeque;
use std::time::Instant;

use crate::canopen::address::NodeId;
use crate::canopen::can::CanBus;
use crate::canopen::frame::CanFrame;
use crate::canopen::link::SdoBus;
use crate::canopen::sdo::{Progress, SdoClient, Transfer};
use crate::error::BusError;

/// Most frames kept for [`CanBus::recv`] while transfers run; older ones are dropped first.
pub const BACKLOG: usize = 1024;

/// Default time a server has to answer each request.
pub const DEFAULT_TIMEOUT: Duration = Duration::from_millis(500);

/// Runs SDO transfers over a [`CanBus`]; implements [`SdoBus`], so a
/// [`CanOpenLink`](crate::canopen::CanOpenLink) works over every CAN interface.
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
            block_size: crate::canopen::sdo::block::MAX_BLOCK_SIZE,
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

    /// Drops the SDO responses that arrived after their transfer ended — duplicates, answers
    /// after a timeout — and keeps every other frame for [`CanBus::recv`]. SDO responses carry
    /// no transaction id: a stale download acknowledgement would otherwise confirm the next
    /// download of the same object before the server executed it. Looks at no more than
    /// [`BACKLOG`] frames, so a flooded bus cannot hold the transfer back.
    fn drop_stale_responses(&mut self, response_cob: u16) -> Result<(), BusError> {
        for _ in 0..BACKLOG {
            match self.bus.recv(Duration::ZERO)? {
                Some(frame) if frame.id() == response_cob => {}
                Some(frame) => self.keep(frame),
                None => break,
            }
        }
        Ok(())
    }

    /// Drives `transfer` to its end: sends its frames, feeds it received frames and the time.
    pub fn run<T: Transfer>(&mut self, transfer: &mut T) -> Result<usize, BusError> {
        self.drop_stale_responses(transfer.response_cob())?;
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

#[cfg(test)]
mod tests {
    use std::collections::VecDeque;
    use std::vec::Vec;

    use super::*;

    /// A bus that delivers what is queued and records what is sent; no server answers.
    #[derive(Default)]
    struct Queued {
        inbound: VecDeque<CanFrame>,
        sent: Vec<CanFrame>,
    }

    impl CanBus for Queued {
        fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
            self.sent.push(*frame);
            Ok(())
        }
        fn recv(&mut self, _: Duration) -> Result<Option<CanFrame>, BusError> {
            Ok(self.inbound.pop_front())
        }
    }

    #[test]
    fn a_stale_acknowledgement_does_not_confirm_the_next_download() {
        let node = NodeId(5);
        let mut bus = Queued::default();
        // The duplicate of the acknowledgement of an earlier download of 2100h:00, and a
        // heartbeat, arrived after that download had ended.
        let stale = CanFrame::new(0x585, &[0x60, 0x00, 0x21, 0x00, 0, 0, 0, 0]).unwrap();
        let heartbeat = CanFrame::new(0x705, &[0x7F]).unwrap();
        bus.inbound.extend([stale, heartbeat]);
        let mut sdo = BlockingSdo::new(bus).with_timeout(Duration::from_millis(20));
        // The server never answers this one: it must not be reported done.
        assert_eq!(
            sdo.download(node, 0x2100, 0, &[1, 2]),
            Err(BusError::Timeout)
        );
        assert_eq!(sdo.bus_mut().sent[0].data()[..4], [0x2B, 0x00, 0x21, 0x00]);
        assert_eq!(
            sdo.recv(Duration::ZERO),
            Ok(Some(heartbeat)),
            "other frames are kept"
        );
    }
}

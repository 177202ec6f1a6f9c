//! A blocking SDO client over any [`CanBus`]: the sans-I/O transfers driven with a real clock.

pub(crate) mod backlog;
pub mod lss;
pub mod scan;

use core::time::Duration;
use std::time::Instant;

use self::backlog::{client_methods, outcome, Backlog, Settings};
use crate::canopen::address::NodeId;
use crate::canopen::can::CanBus;
use crate::canopen::frame::CanFrame;
use crate::canopen::link::SdoBus;
use crate::canopen::sdo::{Progress, Transfer};
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
    backlog: Backlog,
    settings: Settings,
    epoch: Instant,
}

impl<B: CanBus> BlockingSdo<B> {
    /// An SDO client on `bus` with [`DEFAULT_TIMEOUT`]; expedited and segmented transfers only.
    pub fn new(bus: B) -> Self {
        Self {
            bus,
            backlog: Backlog::default(),
            settings: Settings::new(DEFAULT_TIMEOUT),
            epoch: Instant::now(),
        }
    }

    client_methods!();

    fn now(&self) -> Duration {
        self.epoch.elapsed()
    }

    /// Drops the SDO responses that arrived after their transfer ended — duplicates, answers
    /// after a timeout — and keeps every other frame for [`CanBus::recv`]. SDO responses carry
    /// no transaction id: a stale download acknowledgement would otherwise confirm the next
    /// download of the same object before the server executed it. Looks at no more than
    /// [`BACKLOG`] frames, so a flooded bus cannot hold the transfer back.
    fn drop_stale_responses(&mut self, response_cob: u16) -> Result<(), BusError> {
        for _ in 0..BACKLOG {
            match self.bus.recv(Duration::ZERO)? {
                Some(frame) => drop(self.backlog.sort(frame, response_cob)),
                None => break,
            }
        }
        Ok(())
    }

    /// Drives `transfer` to its end: sends its frames, feeds it received frames and the time.
    pub fn run<T: Transfer>(&mut self, transfer: &mut T) -> Result<usize, BusError> {
        let response_cob = transfer.response_cob();
        self.drop_stale_responses(response_cob)?;
        let mut progress = Progress::Pending;
        loop {
            // Drained after the end too: a failure may have queued an abort for the server.
            while let Some(frame) = transfer.poll_transmit() {
                self.bus.send(&frame)?;
            }
            if let Some(result) = outcome(progress, transfer) {
                return result;
            }
            let Some(deadline) = transfer.deadline() else {
                return Err(BusError::Frame("SDO transfer ended without a result"));
            };
            let now = self.now();
            progress = match self.bus.recv(deadline.saturating_sub(now))? {
                Some(frame) => match self.backlog.sort(frame, response_cob) {
                    Some(frame) => transfer.handle(&frame, self.now()),
                    None => Progress::Pending,
                },
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
        let now = self.now();
        let mut transfer = self.settings.upload(node, (index, subindex), out, now);
        self.run(&mut transfer)
    }

    fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        let now = self.now();
        let mut transfer = self.settings.download(node, (index, subindex), data, now);
        self.run(&mut transfer).map(|_| ())
    }
}

/// The bus beside the SDO client: frames that arrived during transfers come first.
impl<B: CanBus> CanBus for BlockingSdo<B> {
    fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.bus.send(frame)
    }

    fn recv(&mut self, timeout: Duration) -> Result<Option<CanFrame>, BusError> {
        match self.backlog.pop() {
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

//! An async SDO client over any [`AsyncCanBus`]: the sans-I/O transfers the blocking
//! [`BlockingSdo`](crate::canopen::client::BlockingSdo) drives, driven with a [`Timer`].
//!
//! The transfers take time as an argument and the [`Timer`] has no clock, so the client keeps
//! a logical one: each request's deadline is the client's kept [`Alarm`](crate::asynch::Alarm) set to the timeout
//! when the request went out, and not moved by frames that are not the transfer's, so foreign
//! traffic cannot stretch it. The alarm is kept from transfer to transfer and moved at each,
//! cheaper than a timer armed afresh per transfer (docs/benchmarks.md, issue 30).

pub mod lss;

use core::pin::pin;
use core::time::Duration;

use crate::asynch::alarm::Aimed;
use crate::asynch::race::{first, ready_now, First};
use crate::asynch::Timer;
use crate::canopen::address::NodeId;
use crate::canopen::can::AsyncCanBus;
use crate::canopen::client::backlog::{client_methods, outcome, Backlog, Settings};
use crate::canopen::client::{BACKLOG, DEFAULT_TIMEOUT};
use crate::canopen::frame::CanFrame;
use crate::canopen::link::AsyncSdoBus;
use crate::canopen::sdo::{AbortCode, Progress, Transfer};
use crate::error::BusError;

/// The abort code sent for a transfer whose future was dropped: CiA 301 has none for "the
/// client gave up"; the general error says nothing it does not know.
pub const CANCEL_CODE: AbortCode = AbortCode::GeneralError;

/// How far the logical clock moves per received response, so a response that restarted the
/// transfer's timer is told apart from one the transfer ignored.
const TICK: Duration = Duration::from_nanos(1);

/// Runs SDO transfers over an [`AsyncCanBus`]; implements [`AsyncSdoBus`], so a
/// [`CanOpenLink`](crate::canopen::CanOpenLink) is an [`AsyncLink`](crate::asynch::AsyncLink)
/// over every async CAN interface.
///
/// As [`BlockingSdo`](crate::canopen::client::BlockingSdo) does, it keeps the frames that
/// arrive during a transfer but are not its own, up to [`BACKLOG`], and hands them out first
/// through its own [`AsyncCanBus::recv`].
///
/// Cancellation: dropping a transfer's future ends the transfer with an SDO abort
/// ([`CANCEL_CODE`]): at once if the bus can send without waiting
/// ([`AsyncCanBus::try_send`]), otherwise before anything else this client sends.
#[derive(Debug)]
pub struct AsyncSdo<B, T: Timer> {
    bus: B,
    /// The transfers' deadline (the only use of the timer), kept from one transfer to the
    /// next and moved at each.
    alarm: T::Alarm,
    backlog: Backlog,
    settings: Settings,
    /// The abort of a transfer whose future was dropped, not yet sent.
    abort_due: Option<CanFrame>,
}

impl<B: AsyncCanBus, T: Timer> AsyncSdo<B, T> {
    /// An SDO client on `bus`, timed by `timer`, with [`DEFAULT_TIMEOUT`]; expedited and
    /// segmented transfers only.
    pub fn new(bus: B, timer: T) -> Self {
        Self {
            bus,
            alarm: timer.alarm(),
            backlog: Backlog::default(),
            settings: Settings::new(DEFAULT_TIMEOUT),
            abort_due: None,
        }
    }

    client_methods!();

    /// Whether the abort of a dropped transfer is still to be sent.
    pub fn abort_pending(&self) -> bool {
        self.abort_due.is_some()
    }

    /// Sends the abort of a dropped transfer, if one is due. Cancel-safe: an abort whose send
    /// was dropped stays due.
    async fn send_due_abort(&mut self) -> Result<(), BusError> {
        if let Some(abort) = self.abort_due {
            self.bus.send(&abort).await?;
            self.abort_due = None;
        }
        Ok(())
    }

    /// Drops the SDO responses that arrived after their transfer ended, keeping every other
    /// frame, as the blocking client does: what is there now, at most [`BACKLOG`] frames.
    async fn drop_stale_responses(&mut self, response_cob: u16) -> Result<(), BusError> {
        for _ in 0..BACKLOG {
            match ready_now(self.bus.recv()).await {
                Some(frame) => drop(self.backlog.sort(frame?, response_cob)),
                None => break,
            }
        }
        Ok(())
    }

    /// Drives `transfer` (started at time zero) to its end: sends its frames, feeds it
    /// received frames and the timer's timeouts. A dropped future aborts the transfer.
    pub async fn run<X: Transfer>(&mut self, transfer: &mut X) -> Result<usize, BusError> {
        self.send_due_abort().await?;
        self.drop_stale_responses(transfer.response_cob()).await?;
        let mut guard = InFlight::arm(self, transfer.abort_frame(CANCEL_CODE));
        let result = guard.sdo.drive(transfer).await;
        guard.disarm();
        result
    }

    async fn drive<X: Transfer>(&mut self, transfer: &mut X) -> Result<usize, BusError> {
        let Self {
            bus,
            alarm,
            backlog,
            ..
        } = self;
        let response_cob = transfer.response_cob();
        let mut now = Duration::ZERO;
        let mut progress = Progress::Pending;
        let mut alarm = Aimed::new(alarm);
        loop {
            // Drained after the end too: a failure may have queued an abort for the server.
            while let Some(frame) = transfer.poll_transmit() {
                bus.send(&frame).await?;
            }
            if let Some(result) = outcome(progress, transfer) {
                return result;
            }
            let Some(deadline) = transfer.deadline() else {
                return Err(BusError::Frame("SDO transfer ended without a result"));
            };
            alarm.aim(deadline, now);
            progress = match first(bus.recv(), pin!(alarm.due())).await {
                First::A(frame) => match backlog.sort(frame?, response_cob) {
                    Some(frame) => {
                        now += TICK;
                        transfer.handle(&frame, now)
                    }
                    None => Progress::Pending,
                },
                First::B(()) => {
                    now = deadline;
                    transfer.handle_timeout(now)
                }
            };
        }
    }
}

/// A transfer under way: if its future is dropped before it ended, its abort is sent at once
/// when the bus allows, else kept due for the next send.
struct InFlight<'a, B: AsyncCanBus, T: Timer> {
    sdo: &'a mut AsyncSdo<B, T>,
    armed: bool,
}

impl<'a, B: AsyncCanBus, T: Timer> InFlight<'a, B, T> {
    fn arm(sdo: &'a mut AsyncSdo<B, T>, abort: Option<CanFrame>) -> Self {
        sdo.abort_due = abort;
        Self {
            sdo,
            armed: abort.is_some(),
        }
    }

    /// The transfer ended (done, failed with its own abort sent, or the bus failed).
    fn disarm(&mut self) {
        self.armed = false;
        self.sdo.abort_due = None;
    }
}

impl<B: AsyncCanBus, T: Timer> Drop for InFlight<'_, B, T> {
    fn drop(&mut self) {
        if !self.armed {
            return;
        }
        if let Some(abort) = self.sdo.abort_due {
            // A bus that fails here fails the next request too; the abort stays due.
            if let Ok(true) = self.sdo.bus.try_send(&abort) {
                self.sdo.abort_due = None;
            }
        }
    }
}

impl<B: AsyncCanBus, T: Timer> AsyncSdoBus for AsyncSdo<B, T> {
    async fn upload(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        out: &mut [u8],
    ) -> Result<usize, BusError> {
        let mut transfer = self
            .settings
            .upload(node, (index, subindex), out, Duration::ZERO);
        self.run(&mut transfer).await
    }

    async fn download(
        &mut self,
        node: NodeId,
        index: u16,
        subindex: u8,
        data: &[u8],
    ) -> Result<(), BusError> {
        let mut transfer = self
            .settings
            .download(node, (index, subindex), data, Duration::ZERO);
        self.run(&mut transfer).await.map(|_| ())
    }
}

/// The bus beside the SDO client: frames that arrived during transfers come first, and a due
/// abort goes out before anything sent.
impl<B: AsyncCanBus, T: Timer> AsyncCanBus for AsyncSdo<B, T> {
    async fn send(&mut self, frame: &CanFrame) -> Result<(), BusError> {
        self.send_due_abort().await?;
        self.bus.send(frame).await
    }

    fn try_send(&mut self, frame: &CanFrame) -> Result<bool, BusError> {
        if let Some(abort) = self.abort_due {
            if !self.bus.try_send(&abort)? {
                return Ok(false);
            }
            self.abort_due = None;
        }
        self.bus.try_send(frame)
    }

    async fn recv(&mut self) -> Result<CanFrame, BusError> {
        match self.backlog.pop() {
            Some(frame) => Ok(frame),
            None => self.bus.recv().await,
        }
    }
}

//! An async LSS master over any [`AsyncCanBus`]: the sans-I/O [`Exchange`] and [`Fastscan`]
//! the blocking [`BlockingLss`](crate::canopen::client::lss::BlockingLss) drives, with the
//! operations of [`request`] shared between the two, driven with a [`Timer`].
//!
//! The [`Timer`] has no clock, so the master keeps a logical one, as the async SDO client
//! does: each deadline is one sleep, started when the step began and kept running across
//! frames, so traffic on the bus cannot hold a command or a Fastscan step past its time.
//!
//! A dropped future leaves nothing to end: LSS has no transfer state on the slave side, and
//! the next operation starts with its own commands.

use core::pin::pin;
use core::time::Duration;

use crate::asynch::race::{first, First};
use crate::asynch::Timer;
use crate::canopen::can::AsyncCanBus;
use crate::canopen::client::lss::{DEFAULT_FASTSCAN_STEP, DEFAULT_TIMEOUT};
use crate::canopen::frame::CanFrame;
use crate::canopen::lss::{
    request, Exchange, Fastscan, FastscanProgress, IdentityWord, LssAddress, LssError, Progress,
    Request,
};
use crate::error::BusError;

/// An LSS master on `bus`, timed by `timer`.
#[derive(Debug)]
pub struct AsyncLss<B, T> {
    bus: B,
    timer: T,
    timeout: Duration,
    step: Duration,
    /// The logical clock: where the last deadline that passed left it.
    now: Duration,
}

impl<B: AsyncCanBus, T: Timer> AsyncLss<B, T> {
    /// A master with [`DEFAULT_TIMEOUT`] and [`DEFAULT_FASTSCAN_STEP`].
    pub fn new(bus: B, timer: T) -> Self {
        Self {
            bus,
            timer,
            timeout: DEFAULT_TIMEOUT,
            step: DEFAULT_FASTSCAN_STEP,
            now: Duration::ZERO,
        }
    }

    /// Sets how long slaves have to answer each command.
    pub fn with_timeout(mut self, timeout: Duration) -> Self {
        self.timeout = timeout;
        self
    }

    /// Sets how long each Fastscan step waits for answers.
    pub fn with_fastscan_step(mut self, step: Duration) -> Self {
        self.step = step;
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

    /// Runs one master operation (see [`request`]): its exchange, then its reading, e.g.
    /// `lss.request(request::store()).await`.
    pub async fn request<R>(&mut self, request: Request<R>) -> Result<R, LssError> {
        let mut exchange = Exchange::new(request.commands(), self.timeout, self.now);
        self.drive(&mut exchange).await?;
        match exchange.progress() {
            Progress::Done(outcome) => request.finish(outcome),
            Progress::Failed(error) => Err(error),
            // `drive` returns once the exchange has no deadline left, which is once it ended.
            Progress::Pending => Err(LssError::NoAnswer),
        }
    }

    /// The whole LSS address of the slave in configuration state.
    pub async fn inquire_address(&mut self) -> Result<LssAddress, LssError> {
        let mut words = [0; 4];
        for (word, value) in IdentityWord::ALL.into_iter().zip(&mut words) {
            *value = self.request(request::inquire(word)).await?;
        }
        Ok(LssAddress::from_words(words))
    }

    /// Fastscan: the LSS address of one non-configured slave, now in configuration state, or
    /// `None` if there is none. The first step waits the command timeout, the others the
    /// Fastscan step.
    pub async fn fastscan(&mut self) -> Result<Option<LssAddress>, LssError> {
        let now = self.now;
        let mut scan = Fastscan::new(self.step, now).with_reset_wait(self.timeout, now);
        self.drive(&mut scan).await?;
        match scan.progress() {
            FastscanProgress::Found(address) => Ok(Some(address)),
            FastscanProgress::NoneLeft => Ok(None),
            FastscanProgress::Failed(error) => Err(error),
            FastscanProgress::Pending => Err(LssError::NoAnswer),
        }
    }

    /// Sends what `machine` queues, feeds it frames and its deadlines, until it has none left.
    async fn drive(&mut self, machine: &mut impl Steps) -> Result<(), BusError> {
        let Self {
            bus, timer, now, ..
        } = self;
        // The sleep until the deadline it was started for; restarted when the deadline moves.
        let mut sleeping_until = None;
        let mut sleep = pin!(timer.sleep(Duration::ZERO));
        loop {
            while let Some(frame) = machine.poll_transmit() {
                bus.send(&frame).await?;
            }
            let Some(deadline) = machine.deadline() else {
                return Ok(());
            };
            if sleeping_until != Some(deadline) {
                sleep.set(timer.sleep(deadline.saturating_sub(*now)));
                sleeping_until = Some(deadline);
            }
            match first(bus.recv(), sleep.as_mut()).await {
                First::A(frame) => machine.handle(&frame?, *now),
                First::B(()) => {
                    *now = deadline;
                    // A finished sleep is not polled again.
                    sleeping_until = None;
                    sleep.set(timer.sleep(Duration::ZERO));
                    machine.handle_timeout(*now);
                }
            }
        }
    }
}

/// What [`AsyncLss::drive`] needs of an exchange or a Fastscan: both are driven alike.
trait Steps {
    fn poll_transmit(&mut self) -> Option<CanFrame>;
    /// When the machine waits for time next; `None` once it has ended.
    fn deadline(&self) -> Option<Duration>;
    fn handle(&mut self, frame: &CanFrame, now: Duration);
    fn handle_timeout(&mut self, now: Duration);
}

impl Steps for Exchange {
    fn poll_transmit(&mut self) -> Option<CanFrame> {
        Exchange::poll_transmit(self)
    }
    fn deadline(&self) -> Option<Duration> {
        Exchange::deadline(self)
    }
    fn handle(&mut self, frame: &CanFrame, now: Duration) {
        Exchange::handle(self, frame, now);
    }
    fn handle_timeout(&mut self, now: Duration) {
        Exchange::handle_timeout(self, now);
    }
}

impl Steps for Fastscan {
    fn poll_transmit(&mut self) -> Option<CanFrame> {
        Fastscan::poll_transmit(self)
    }
    fn deadline(&self) -> Option<Duration> {
        Fastscan::deadline(self)
    }
    fn handle(&mut self, frame: &CanFrame, now: Duration) {
        Fastscan::handle(self, frame, now);
    }
    fn handle_timeout(&mut self, now: Duration) {
        Fastscan::handle_timeout(self, now);
    }
}

#[cfg(all(test, feature = "server"))]
mod tests;

//! A blocking LSS master over any [`CanBus`]: the sans-I/O [`Exchange`] and [`Fastscan`] driven
//! with the machine's clock. Frames that are not LSS answers (heartbeats, PDOs) are skipped.

use core::ops::RangeInclusive;
use core::time::Duration;
use std::time::Instant;

use crate::canopen::can::CanBus;
use crate::canopen::lss::{
    request, BitTiming, Exchange, Fastscan, FastscanProgress, IdentityWord, LssAddress, LssError,
    LssMode, Outcome, Progress, Request,
};

/// Default time slaves have to answer each command (python canopen 2.4.1 waits 500 ms too).
pub const DEFAULT_TIMEOUT: Duration = Duration::from_millis(500);

/// Default time each Fastscan step waits: silence is an answer, so every step lasts this long.
pub const DEFAULT_FASTSCAN_STEP: Duration = Duration::from_millis(20);

/// An LSS master on `bus`.
#[derive(Debug)]
pub struct BlockingLss<B> {
    bus: B,
    timeout: Duration,
    step: Duration,
    epoch: Instant,
}

impl<B: CanBus> BlockingLss<B> {
    /// A master with [`DEFAULT_TIMEOUT`] and [`DEFAULT_FASTSCAN_STEP`].
    pub fn new(bus: B) -> Self {
        Self {
            bus,
            timeout: DEFAULT_TIMEOUT,
            step: DEFAULT_FASTSCAN_STEP,
            epoch: Instant::now(),
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

    fn now(&self) -> Duration {
        self.epoch.elapsed()
    }

    /// Drives `exchange` to its end.
    pub fn run(&mut self, exchange: &mut Exchange) -> Result<Outcome, LssError> {
        loop {
            while let Some(frame) = exchange.poll_transmit() {
                self.bus.send(&frame)?;
            }
            let progress = match exchange.deadline() {
                None => exchange.progress(),
                Some(deadline) => match self.bus.recv(deadline.saturating_sub(self.now()))? {
                    // The deadline is checked after every frame too: a bus busy with other
                    // traffic must not keep the exchange waiting past it.
                    Some(frame) => match exchange.handle(&frame, self.now()) {
                        Progress::Pending => exchange.handle_timeout(self.now()),
                        ended => ended,
                    },
                    None => exchange.handle_timeout(self.now()),
                },
            };
            match progress {
                Progress::Pending => {}
                Progress::Done(outcome) => return Ok(outcome),
                Progress::Failed(error) => return Err(error),
            }
        }
    }

    /// Runs one master operation (see [`request`]): its exchange, then its reading.
    pub fn request<T>(&mut self, request: Request<T>) -> Result<T, LssError> {
        let mut exchange = Exchange::new(request.commands(), self.timeout, self.now());
        request.finish(self.run(&mut exchange)?)
    }

    /// Switch state global: every slave to `mode` (no answer).
    pub fn switch_global(&mut self, mode: LssMode) -> Result<(), LssError> {
        self.request(request::switch_global(mode))
    }

    /// Switch state selective: the slave at `address` enters configuration state. No answer is
    /// [`LssError::NoAnswer`]; two are [`LssError::SeveralAnswers`].
    pub fn switch_selective(&mut self, address: LssAddress) -> Result<(), LssError> {
        self.request(request::switch_selective(address))
    }

    /// Configure node id (the slave in configuration state); `raw` must be 1-127 or 255 (none):
    /// anything else is refused here, nothing is sent. Takes effect at the node's next reset;
    /// nothing is stored ([`BlockingLss::store`] does that).
    pub fn configure_node_id(&mut self, raw: u8) -> Result<(), LssError> {
        self.request(request::configure_node_id(raw)?)
    }

    /// Configure bit timing from the CiA 305 table; a refusal carries the slave's error code.
    pub fn configure_bit_timing(&mut self, timing: BitTiming) -> Result<(), LssError> {
        self.request(request::configure_bit_timing(timing))
    }

    /// Activate bit timing on every slave after `delay_ms` (no answer).
    pub fn activate_bit_timing(&mut self, delay_ms: u16) -> Result<(), LssError> {
        self.request(request::activate_bit_timing(delay_ms))
    }

    /// Store configuration: the slave keeps its node id and bit timing across a power cycle.
    pub fn store(&mut self) -> Result<(), LssError> {
        self.request(request::store())
    }

    /// One word of the LSS address of the slave in configuration state.
    pub fn inquire(&mut self, word: IdentityWord) -> Result<u32, LssError> {
        self.request(request::inquire(word))
    }

    /// The whole LSS address of the slave in configuration state.
    pub fn inquire_address(&mut self) -> Result<LssAddress, LssError> {
        let mut words = [0; 4];
        for (word, value) in IdentityWord::ALL.into_iter().zip(&mut words) {
            *value = self.inquire(word)?;
        }
        Ok(LssAddress::from_words(words))
    }

    /// The active node id of the slave in configuration state (255: none).
    pub fn inquire_node_id(&mut self) -> Result<u8, LssError> {
        self.request(request::inquire_node_id())
    }

    /// Identify remote slave: how many slaves of `vendor_id` and `product_code` have a revision
    /// and serial number within the ranges.
    pub fn identify_remote(
        &mut self,
        vendor_id: u32,
        product_code: u32,
        revision: RangeInclusive<u32>,
        serial: RangeInclusive<u32>,
    ) -> Result<usize, LssError> {
        self.request(request::identify_remote(
            vendor_id,
            product_code,
            revision,
            serial,
        ))
    }

    /// Identify non-configured remote slave: how many slaves have no node id.
    pub fn identify_non_configured(&mut self) -> Result<usize, LssError> {
        self.request(request::identify_non_configured())
    }

    /// Fastscan: the LSS address of one non-configured slave, now in configuration state, or
    /// `None` if there is none. The first step waits the command timeout, the others the
    /// Fastscan step.
    pub fn fastscan(&mut self) -> Result<Option<LssAddress>, LssError> {
        let now = self.now();
        let mut scan = Fastscan::new(self.step, now).with_reset_wait(self.timeout, now);
        loop {
            while let Some(frame) = scan.poll_transmit() {
                self.bus.send(&frame)?;
            }
            let Some(deadline) = scan.deadline() else {
                break;
            };
            if let Some(frame) = self.bus.recv(deadline.saturating_sub(self.now()))? {
                scan.handle(&frame, self.now());
            }
            scan.handle_timeout(self.now());
        }
        match scan.progress() {
            FastscanProgress::Found(address) => Ok(Some(address)),
            FastscanProgress::NoneLeft => Ok(None),
            FastscanProgress::Failed(error) => Err(error),
            FastscanProgress::Pending => Err(LssError::NoAnswer),
        }
    }
}

#[cfg(all(test, feature = "server"))]
mod tests;

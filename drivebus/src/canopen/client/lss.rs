//! A blocking LSS master over any [`CanBus`]: the sans-I/O [`Exchange`] and [`Fastscan`] driven
//! with the machine's clock. Frames that are not LSS answers (heartbeats, PDOs) are skipped.

use core::ops::RangeInclusive;
use core::time::Duration;
use std::time::Instant;

use crate::canopen::can::CanBus;
use crate::canopen::lss::command::RangePart;
use crate::canopen::lss::{
    BitTiming, Command, Exchange, Fastscan, FastscanProgress, IdentityWord, LssAddress, LssError,
    LssMode, NewNodeId, Outcome, Progress, Response,
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

    fn exchange(&mut self, commands: &[Command]) -> Result<Outcome, LssError> {
        let mut exchange = Exchange::new(commands, self.timeout, self.now());
        self.run(&mut exchange)
    }

    /// The answer to one command only one slave may answer.
    fn ask(&mut self, command: Command) -> Result<Response, LssError> {
        self.exchange(&[command])?
            .response
            .ok_or(LssError::NoAnswer)
    }

    /// Switch state global: every slave to `mode` (no answer).
    pub fn switch_global(&mut self, mode: LssMode) -> Result<(), LssError> {
        self.exchange(&[Command::SwitchGlobal(mode)]).map(|_| ())
    }

    /// Switch state selective: the slave at `address` enters configuration state. No answer is
    /// [`LssError::NoAnswer`]; two are [`LssError::SeveralAnswers`].
    pub fn switch_selective(&mut self, address: LssAddress) -> Result<(), LssError> {
        let commands = IdentityWord::ALL.map(|word| {
            Command::SwitchSelective(word, address.words()[usize::from(word.position())])
        });
        self.exchange(&commands).map(|_| ())
    }

    /// Configure node id (the slave in configuration state); `raw` must be 1-127 or 255 (none):
    /// anything else is refused here, nothing is sent. Takes effect at the node's next reset;
    /// nothing is stored ([`BlockingLss::store`] does that).
    pub fn configure_node_id(&mut self, raw: u8) -> Result<(), LssError> {
        let id = NewNodeId::new(raw)?;
        confirmed(self.ask(Command::ConfigureNodeId(id))?)
    }

    /// Configure bit timing from the CiA 305 table; a refusal carries the slave's error code.
    pub fn configure_bit_timing(&mut self, timing: BitTiming) -> Result<(), LssError> {
        let command = Command::ConfigureBitTiming {
            table: 0,
            index: timing.index(),
        };
        confirmed(self.ask(command)?)
    }

    /// Activate bit timing on every slave after `delay_ms` (no answer).
    pub fn activate_bit_timing(&mut self, delay_ms: u16) -> Result<(), LssError> {
        self.exchange(&[Command::ActivateBitTiming { delay_ms }])
            .map(|_| ())
    }

    /// Store configuration: the slave keeps its node id and bit timing across a power cycle.
    pub fn store(&mut self) -> Result<(), LssError> {
        confirmed(self.ask(Command::Store)?)
    }

    /// One word of the LSS address of the slave in configuration state.
    pub fn inquire(&mut self, word: IdentityWord) -> Result<u32, LssError> {
        match self.ask(Command::Inquire(word))? {
            Response::Inquired(_, value) => Ok(value),
            _ => Err(LssError::NoAnswer),
        }
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
        match self.ask(Command::InquireNodeId)? {
            Response::NodeId(id) => Ok(id),
            _ => Err(LssError::NoAnswer),
        }
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
        let values = [
            vendor_id,
            product_code,
            *revision.start(),
            *revision.end(),
            *serial.start(),
            *serial.end(),
        ];
        let commands: [Command; 6] =
            core::array::from_fn(|i| Command::IdentifyRemote(RangePart::ALL[i], values[i]));
        Ok(self.exchange(&commands)?.count)
    }

    /// Identify non-configured remote slave: how many slaves have no node id.
    pub fn identify_non_configured(&mut self) -> Result<usize, LssError> {
        Ok(self.exchange(&[Command::IdentifyNonConfigured])?.count)
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

/// The verdict of a configure or store confirmation.
fn confirmed(response: Response) -> Result<(), LssError> {
    match response {
        Response::Confirmed(_, verdict) => verdict.map_err(LssError::Refused),
        _ => Err(LssError::NoAnswer),
    }
}

#[cfg(all(test, feature = "server"))]
mod tests;

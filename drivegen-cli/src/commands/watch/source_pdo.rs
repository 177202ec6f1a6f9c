//! Samples by PDO (`watch --pdo`, CANopen): each node's watched parameters come in a TPDO the
//! drive sends at every SYNC the watch produces, or by its event timer; while watching, no SDO
//! request goes out. The TPDO configuration the watch changed is written back when it ends,
//! on Ctrl-C and on errors too (see [`TpdoSetup`]'s `Drop`).

use std::time::{Duration, Instant};

use drivebus::canopen::frame::cob;
use drivebus::canopen::{CanBus, CanFrame};

use super::interrupt::Interrupt;
use super::pdo_plan::Trigger;
use super::pdo_slots::Slots;
use super::sample::{Sample, Source};
use super::tpdo_setup::{Node, TpdoSetup};
use crate::connect::hold;
use crate::drives::Outcome;
use crate::error::CliError;

/// Longest single wait on the bus: how late a Ctrl-C is noticed at most while waiting.
const NAP: Duration = Duration::from_millis(20);

/// The most SYNC intervals the watch makes up for after it was held up.
const CATCH_UP: u32 = 4;

/// How the watch runs.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// SYNC or the event timer.
    pub trigger: Trigger,
    /// Between SYNCs.
    pub interval: Duration,
    /// How long a node has to send its TPDO.
    pub timeout: Duration,
    /// Send NMT Start before and Enter Pre-Operational after the watch.
    pub start: bool,
}

/// The nodes' TPDOs on one CAN bus.
pub struct PdoWatch<'d> {
    /// The TPDOs set up (and put back when the watch is dropped).
    setup: TpdoSetup<'d>,
    settings: Settings,
    interrupt: Interrupt,
    start: Instant,
    slots: Slots,
    /// When the next SYNC is due (SYNC mode).
    next_sync: Instant,
    /// Since when no sample was given (event-timer mode: a silence that long is a timeout).
    quiet_since: Instant,
    samples: u64,
}

impl<'d> PdoWatch<'d> {
    /// Watches the nodes' TPDOs as `setup` set them up (see [`TpdoSetup::begin`], given the
    /// same trigger and start as `settings`).
    pub fn new(setup: TpdoSetup<'d>, settings: Settings, interrupt: Interrupt) -> Self {
        let now = Instant::now();
        Self {
            slots: Slots::new(setup.nodes().len(), settings.trigger != Trigger::Sync),
            setup,
            settings,
            interrupt,
            start: now,
            next_sync: now,
            quiet_since: now,
            samples: 0,
        }
    }

    /// Puts back what the watch changed ([`TpdoSetup::restore`]).
    pub fn restore(&mut self) -> Result<(), CliError> {
        self.setup.restore()
    }

    /// Sends a SYNC if one is due (SYNC mode), then waits on the bus until the next is due,
    /// the oldest slot times out, or a short nap passed, filling a slot with the TPDO that came.
    fn turn(&mut self) -> Result<(), CliError> {
        let now = Instant::now();
        let mut wake = now + NAP;
        if self.settings.trigger == Trigger::Sync {
            if now >= self.next_sync {
                let sync =
                    CanFrame::new(cob::SYNC, &[]).map_err(|e| CliError::Io(e.to_string()))?;
                hold(self.setup.bus())
                    .send(&sync)
                    .map_err(|e| CliError::Io(format!("SYNC: {e}")))?;
                self.slots.sync(now, self.time(now));
                // On schedule: a SYNC sent late (a wake-up the system delayed) does not move
                // the next ones, so the rate holds; after a stall of more than a few intervals
                // the schedule starts again from now rather than sending a burst.
                self.next_sync += self.settings.interval;
                if self.next_sync + CATCH_UP * self.settings.interval < now {
                    self.next_sync = now;
                }
            }
            wake = wake.min(self.next_sync);
        }
        if let Some(deadline) = self.slots.deadline(self.settings.timeout) {
            wake = wake.min(deadline);
        }
        let wait = wake.saturating_duration_since(Instant::now());
        let frame = hold(self.setup.bus()).recv(wait);
        let frame = frame.map_err(|e| CliError::Io(format!("CAN bus: {e}")))?;
        let Some(frame) = frame else {
            return Ok(());
        };
        let node = self
            .setup
            .nodes()
            .iter()
            .position(|n| !frame.is_remote() && n.choice.can_id() == frame.id());
        if let Some(i) = node {
            let at = Instant::now();
            self.slots.fill(i, frame.data().to_vec(), at, self.time(at));
        }
        Ok(())
    }

    /// Seconds from the start of the watch to `at`.
    fn time(&self, at: Instant) -> f64 {
        at.duration_since(self.start).as_secs_f64()
    }

    /// A node's values from its TPDO payload, or why there are none.
    fn outcome(&self, node: &Node, payload: Option<Vec<u8>>) -> Outcome {
        let Some(payload) = payload else {
            let hint = match self.samples {
                0 if !self.settings.start => ": is the node Operational? (--start starts it)",
                _ => "",
            };
            return Err(CliError::Io(format!(
                "no TPDO {} (COB-ID {:03X}h) from node {} within {} ms{hint}",
                node.choice.watched.number,
                node.choice.can_id(),
                node.id.0,
                self.settings.timeout.as_millis()
            )));
        };
        self.setup.values(node, &payload)
    }
}

impl Source for PdoWatch<'_> {
    fn next(&mut self) -> Result<Option<Sample>, CliError> {
        let (time, payloads) = loop {
            if self.interrupt.raised() {
                return Ok(None);
            }
            let now = Instant::now();
            if let Some(ready) = self.slots.ready(now, self.settings.timeout) {
                break ready;
            }
            let by_event = self.settings.trigger != Trigger::Sync;
            if by_event && self.slots.deadline(self.settings.timeout).is_none() {
                // Nothing came at all for a timeout: every node is late.
                if now.duration_since(self.quiet_since) >= self.settings.timeout {
                    break (self.time(now), vec![None; self.setup.nodes().len()]);
                }
            }
            self.turn()?;
        };
        self.quiet_since = Instant::now();
        let drives = self
            .setup
            .nodes()
            .iter()
            .zip(payloads)
            .map(|(node, payload)| self.outcome(node, payload))
            .collect();
        self.samples += 1;
        Ok(Some(Sample { time, drives }))
    }
}

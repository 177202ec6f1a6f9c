//! Samples by PDO (`watch --pdo`, CANopen): each node's watched parameters come in a TPDO the
//! drive sends at every SYNC the watch produces, or by its event timer; while watching, no SDO
//! request goes out. The TPDO configuration the watch changed is written back when it ends,
//! on Ctrl-C and on errors too (see [`PdoWatch`]'s `Drop`).

use std::time::{Duration, Instant};

use drivebus::canopen::frame::cob;
use drivebus::canopen::nmt::NmtCommand;
use drivebus::canopen::{CanBus, CanFrame, NodeId};
use drivebus::interpret;
use drivegen::ir::{Device, Parameter};

use super::interrupt::Interrupt;
use super::pdo_plan::{self, Choice, Trigger};
use super::pdo_slots::Slots;
use super::sample::{Sample, Source};
use super::tpdo_config::TpdoConfig;
use crate::connect::{hold, Session, SharedCan};
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

/// One node's watch.
struct Node {
    id: NodeId,
    choice: Choice,
    /// What to write back; set before the first write, so a half-written TPDO is restored too.
    restore: Option<TpdoConfig>,
}

/// The nodes' TPDOs on one CAN bus.
pub struct PdoWatch<'d> {
    bus: SharedCan,
    device: &'d Device,
    parameters: Vec<&'d Parameter>,
    nodes: Vec<Node>,
    settings: Settings,
    interrupt: Interrupt,
    start: Instant,
    slots: Slots,
    /// When the next SYNC is due (SYNC mode).
    next_sync: Instant,
    /// Since when no sample was given (event-timer mode: a silence that long is a timeout).
    quiet_since: Instant,
    started: bool,
    samples: u64,
}

impl<'d> PdoWatch<'d> {
    /// Plans every node's TPDO (the nodes of `drives`, sessions on one SDO client; reading the drives' configuration by SDO; a parameter that
    /// cannot be mapped, or a node without a TPDO to map into, is refused before anything is
    /// written), then writes the TPDOs that need it and, with `start`, starts the nodes.
    pub fn begin(
        drives: &[Session<'_>],
        device: &'d Device,
        parameters: &[&'d Parameter],
        settings: Settings,
        interrupt: Interrupt,
    ) -> Result<Self, CliError> {
        let entries = pdo_plan::entries(parameters).map_err(|refused| {
            CliError::Usage(format!("cannot watch by PDO:\n  {}", refused.join("\n  ")))
        })?;
        let (bus, ids) = can_nodes(drives)?;
        let described = pdo_plan::described_tpdos(device);
        let mut nodes = Vec::with_capacity(ids.len());
        for id in ids {
            let held = read_tpdos(&bus, id, &described)?;
            let taken: Vec<u16> = nodes.iter().map(|n: &Node| n.choice.can_id()).collect();
            let choice = pdo_plan::choose(&held, &entries, settings.trigger, id, &taken);
            let choice = choice.map_err(|why| {
                CliError::Usage(format!("cannot watch node {} by PDO: {why}", id.0))
            })?;
            nodes.push(Node {
                id,
                choice,
                restore: None,
            });
        }
        let now = Instant::now();
        let mut watch = Self {
            bus,
            device,
            parameters: parameters.to_vec(),
            slots: Slots::new(nodes.len(), settings.trigger != Trigger::Sync),
            nodes,
            settings,
            interrupt,
            start: now,
            next_sync: now,
            quiet_since: now,
            started: false,
            samples: 0,
        };
        watch.program()?;
        let now = Instant::now();
        (watch.start, watch.next_sync, watch.quiet_since) = (now, now, now);
        Ok(watch)
    }

    /// Writes each TPDO the watch needs changed, then starts the nodes if asked.
    fn program(&mut self) -> Result<(), CliError> {
        for node in &mut self.nodes {
            let Some(saved) = &node.choice.saved else {
                continue;
            };
            node.restore = Some(saved.clone());
            let written = node.choice.watched.write(&mut *hold(&self.bus), node.id);
            written.map_err(|cause| tpdo_error(node, "cannot configure", cause))?;
            eprintln!(
                "node {}: TPDO {} mapped for the watch (restored at the end)",
                node.id.0, node.choice.watched.number
            );
        }
        if self.settings.start {
            self.started = true;
            self.nmt(NmtCommand::Start)?;
        }
        Ok(())
    }

    /// Sends `command` to every watched node.
    fn nmt(&self, command: NmtCommand) -> Result<(), CliError> {
        let mut bus = hold(&self.bus);
        for node in &self.nodes {
            bus.send(&command.frame(Some(node.id)))
                .map_err(|e| CliError::Io(format!("NMT to node {}: {e}", node.id.0)))?;
        }
        Ok(())
    }

    /// Puts back what the watch changed: the nodes' NMT state (if it started them), then each
    /// TPDO's configuration as it was read. Every node is tried; the first failure is returned.
    pub fn restore(&mut self) -> Result<(), CliError> {
        let mut first_error = None;
        if std::mem::take(&mut self.started) {
            first_error = self.nmt(NmtCommand::EnterPreOperational).err();
        }
        for node in &mut self.nodes {
            let Some(saved) = node.restore.take() else {
                continue;
            };
            let written = saved.write(&mut *hold(&self.bus), node.id);
            if let Err(cause) = written {
                let error = tpdo_error(node, "cannot restore", cause);
                first_error.get_or_insert(error);
            }
        }
        first_error.map_or(Ok(()), Err)
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
                hold(&self.bus)
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
        let frame = hold(&self.bus).recv(wait);
        let frame = frame.map_err(|e| CliError::Io(format!("CAN bus: {e}")))?;
        let Some(frame) = frame else {
            return Ok(());
        };
        let node = self
            .nodes
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
        let choice = &node.choice;
        let Some(payload) = payload else {
            let hint = match self.samples {
                0 if !self.settings.start => ": is the node Operational? (--start starts it)",
                _ => "",
            };
            return Err(CliError::Io(format!(
                "no TPDO {} (COB-ID {:03X}h) from node {} within {} ms{hint}",
                choice.watched.number,
                choice.can_id(),
                node.id.0,
                self.settings.timeout.as_millis()
            )));
        };
        if payload.len() < choice.payload_len() {
            return Err(CliError::Io(format!(
                "TPDO {} from node {} has {} bytes, its mapping {}",
                choice.watched.number,
                node.id.0,
                payload.len(),
                choice.payload_len()
            )));
        }
        let shown = self.parameters.iter().zip(&choice.offsets).map(|(p, &at)| {
            let bytes = drivegen::ir::pdo_bits(p.data_type) as usize / 8;
            interpret::show(self.device, *p, &payload[at..at + bytes])
        });
        Ok(shown.collect())
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
                    break (self.time(now), vec![None; self.nodes.len()]);
                }
            }
            self.turn()?;
        };
        self.quiet_since = Instant::now();
        let drives = self
            .nodes
            .iter()
            .zip(payloads)
            .map(|(node, payload)| self.outcome(node, payload))
            .collect();
        self.samples += 1;
        Ok(Some(Sample { time, drives }))
    }
}

/// Whatever ended the watch, the drives get their TPDOs back.
impl Drop for PdoWatch<'_> {
    fn drop(&mut self) {
        if let Err(e) = self.restore() {
            eprintln!("error: {e}");
        }
    }
}

/// The CAN bus the drives share, and their node ids; refused on another bus.
fn can_nodes(drives: &[Session<'_>]) -> Result<(SharedCan, Vec<NodeId>), CliError> {
    let mut bus = None;
    let mut ids = Vec::new();
    for session in drives {
        let (shared, id) = session.can().ok_or_else(|| {
            CliError::Usage(format!(
                "--pdo watches CANopen drives (--can); {} has no PDOs",
                session.protocol()
            ))
        })?;
        bus.get_or_insert(shared);
        ids.push(id);
    }
    let bus = bus.ok_or_else(|| CliError::Usage("--pdo: no drive named".into()))?;
    Ok((bus, ids))
}

/// The described TPDOs of node `id` as it holds them now.
fn read_tpdos(bus: &SharedCan, id: NodeId, numbers: &[u16]) -> Result<Vec<TpdoConfig>, CliError> {
    numbers
        .iter()
        .map(|&n| {
            TpdoConfig::read(&mut *hold(bus), id, n).map_err(|cause| CliError::Bus {
                target: format!("node {}", id.0),
                parameter: format!("TPDO {n} configuration"),
                cause,
            })
        })
        .collect()
}

/// A failed write of a node's TPDO.
fn tpdo_error(node: &Node, what: &str, cause: drivebus::BusError) -> CliError {
    CliError::Bus {
        target: format!("node {}", node.id.0),
        parameter: format!("{what} TPDO {}", node.choice.watched.number),
        cause,
    }
}

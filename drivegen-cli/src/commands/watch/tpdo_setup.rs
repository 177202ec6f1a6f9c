//! The TPDOs a PDO reader needs, set up on the nodes and put back: each node's TPDO chosen
//! (its configuration read by SDO first), written where it must change, the nodes started if
//! asked, and, when the reader ends, the nodes' NMT state and each TPDO's configuration written
//! back. Shared by `watch --pdo` (which reads the TPDOs on SYNC or event timer) and the gateway
//! (whose poller reads them beside other drives' SDO polls), each showing what the set-up tells
//! ([`Notice`]) its own way.

use drivebus::canopen::nmt::NmtCommand;
use drivebus::canopen::{CanBus, NodeId};
use drivebus::interpret;
use drivegen::ir::{Device, Parameter};

use super::pdo_plan::{self, Choice, Trigger};
use super::tpdo_config::TpdoConfig;
use super::tpdo_notice::{Notice, Report};
use crate::connect::{hold, Session, SharedCan};
use crate::drives::Outcome;
use crate::error::CliError;

/// One node's TPDO.
pub struct Node {
    /// The node.
    pub id: NodeId,
    /// Its TPDO as read, and as the reader needs it.
    pub choice: Choice,
    /// What to write back; set before the first write, so a half-written TPDO is restored too.
    restore: Option<TpdoConfig>,
}

/// The nodes' TPDOs on one CAN bus, set up for `parameters`; put back when dropped.
pub struct TpdoSetup<'d> {
    bus: SharedCan,
    device: &'d Device,
    parameters: Vec<&'d Parameter>,
    nodes: Vec<Node>,
    /// Whether the nodes were sent NMT Start (and go back to Pre-Operational at the end).
    started: bool,
    /// Where what the set-up tells goes.
    report: Report,
}

impl<'d> TpdoSetup<'d> {
    /// Plans every node's TPDO (the nodes of `drives`, sessions on one SDO client; reading the
    /// drives' configuration by SDO; a parameter that cannot be mapped, or a node without a
    /// TPDO to map into, is refused before anything is written, as a [`CliError::Usage`]),
    /// never on a CAN identifier in `taken` (other readers' TPDOs on the bus), then writes the
    /// TPDOs that need it and, with `start`, starts the nodes. What it tells (a TPDO mapped, an
    /// identifier clash, a TPDO not put back) goes to `report`.
    pub fn begin(
        drives: &[Session<'_>],
        device: &'d Device,
        parameters: &[&'d Parameter],
        trigger: Trigger,
        start: bool,
        taken: &[u16],
        report: Report,
    ) -> Result<Self, CliError> {
        let entries = pdo_plan::entries(parameters).map_err(|refused| {
            CliError::Usage(format!("cannot watch by PDO:\n  {}", refused.join("\n  ")))
        })?;
        let (bus, ids) = can_nodes(drives)?;
        let described = pdo_plan::described_tpdos(device);
        let mut nodes = Vec::with_capacity(ids.len());
        for id in ids {
            let held = read_tpdos(&bus, id, &described)?;
            let mut used: Vec<u16> = nodes.iter().map(|n: &Node| n.choice.can_id()).collect();
            used.extend_from_slice(taken);
            let choice = pdo_plan::choose(&held, &entries, trigger, id, &used);
            let choice = choice.map_err(|why| {
                CliError::Usage(format!("cannot watch node {} by PDO: {why}", id.0))
            })?;
            warn_clashes(id, &held, &choice, &used, report);
            nodes.push(Node {
                id,
                choice,
                restore: None,
            });
        }
        let mut setup = Self {
            bus,
            device,
            parameters: parameters.to_vec(),
            nodes,
            started: false,
            report,
        };
        setup.program(start)?;
        Ok(setup)
    }

    /// Writes each TPDO that needs changing, then starts the nodes if asked.
    fn program(&mut self, start: bool) -> Result<(), CliError> {
        for node in &mut self.nodes {
            let Some(saved) = &node.choice.saved else {
                continue;
            };
            node.restore = Some(saved.clone());
            let written = node.choice.watched.write(&mut *hold(&self.bus), node.id);
            written.map_err(|cause| tpdo_error(node, "cannot configure", cause))?;
            (self.report)(&Notice::Mapped {
                node: node.id.0,
                tpdo: node.choice.watched.number,
            });
        }
        if start {
            self.started = true;
            self.nmt(NmtCommand::Start)?;
        }
        Ok(())
    }

    /// Sends `command` to every node.
    fn nmt(&self, command: NmtCommand) -> Result<(), CliError> {
        let mut bus = hold(&self.bus);
        for node in &self.nodes {
            bus.send(&command.frame(Some(node.id)))
                .map_err(|e| CliError::Io(format!("NMT to node {}: {e}", node.id.0)))?;
        }
        Ok(())
    }

    /// Puts back what the setup changed: the nodes' NMT state (if it started them), then each
    /// TPDO's configuration as it was read. Every node is tried; the first failure is returned.
    /// Done once: a second call (or the drop after it) writes nothing.
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

    /// The bus the TPDOs come on.
    pub fn bus(&self) -> &SharedCan {
        &self.bus
    }

    /// The nodes, in the order of the sessions given to [`begin`](Self::begin).
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The values `node` (one of [`nodes`](Self::nodes)) sent in `payload`, or
    /// why there are none (a payload shorter than its mapping).
    pub fn values(&self, node: &Node, payload: &[u8]) -> Outcome {
        let choice = &node.choice;
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

/// Whatever ended the reader, the drives get their TPDOs back.
impl Drop for TpdoSetup<'_> {
    fn drop(&mut self) {
        if let Err(e) = self.restore() {
            (self.report)(&Notice::NotRestored(e));
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

/// Warns (to `report`) of the TPDOs `id` sends besides the chosen one on an identifier another
/// reader's TPDO uses (a drive whose TPDO identifiers do not follow its node id): they are left
/// as they are, so both go out on it and the values may mix.
fn warn_clashes(id: NodeId, held: &[TpdoConfig], choice: &Choice, used: &[u16], report: Report) {
    let chosen = choice.watched.number;
    for tpdo in held {
        if tpdo.is_valid() && tpdo.number != chosen && used.contains(&tpdo.can_id()) {
            report(&Notice::Clash {
                node: id.0,
                tpdo: tpdo.number,
                can_id: tpdo.can_id(),
            });
        }
    }
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

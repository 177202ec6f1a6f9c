//! A CANopen node: boot-up, NMT state, heartbeat producer, the SDO server, the PDOs, the SRDOs
//! and, when
//! the description makes the drive an LSS slave, LSS (CiA 305), sans-I/O, plus a blocking loop
//! over any CAN backend.
//!
//! A node LSS gave no node id (FFh) is silent but for LSS: no boot-up, heartbeat, SDO or EMCY
//! until a master configures one. A new node id takes effect at the next NMT reset (or at once
//! for a node that had none, when the master switches it back to LSS waiting state); the node
//! then boots up at it. Only a stored one survives [`Node::power_cycle`].

use std::time::Duration;

use drivebus::canopen::emcy::{Emcy, ErrorRegister};
use drivebus::canopen::frame::cob;
use drivebus::canopen::lss::{LssSlave, SlaveEvent, UNCONFIGURED};
use drivebus::canopen::nmt::{heartbeat_frame, NmtCommand, NmtState};
use drivebus::canopen::sdo::server::SdoServer;
use drivebus::canopen::{CanBus, CanFrame, NodeId};
use drivebus::BusError;

use super::pdo::Pdos;
use super::srdo::Srdos;
use super::Dictionary;
use crate::behaviour::object;
use crate::Simulator;

/// Settings of a simulated node.
#[derive(Debug, Clone, Copy)]
pub struct NodeConfig {
    /// Node id.
    pub node: NodeId,
    /// Heartbeat period when the description has no 1017h object (`None`: no heartbeat).
    pub heartbeat: Option<Duration>,
}

/// A simulated CANopen node.
#[derive(Debug)]
pub struct Node {
    config: NodeConfig,
    sim: Simulator,
    sdo: SdoServer<Dictionary>,
    state: NmtState,
    next_heartbeat: Duration,
    reported_fault: Option<u16>,
    pdos: Pdos,
    srdos: Srdos,
    variant: Option<String>,
    lss: Option<LssSlave>,
    /// LSS left the node without a node id: it is silent but for LSS.
    silent: bool,
}

impl Node {
    /// A node serving `sim`'s drive; it is INITIALISING until [`Node::boot`]. Node-relative
    /// defaults take their value on `config.node`.
    pub fn new(sim: Simulator, config: NodeConfig, variant: Option<&str>) -> Self {
        sim.with(|drive| drive.at_node(config.node.0));
        let dictionary =
            sim.with(|drive| Dictionary::new(sim.clone(), drive.store().device(), variant));
        let srdos = sim.with(|drive| Srdos::new(drive.store(), config.node));
        let lss = sim.with(|drive| super::lss::slave(drive.store(), config.node.0, 1_000_000));
        Self {
            config,
            sim,
            sdo: SdoServer::new(config.node, dictionary),
            state: NmtState::Initializing,
            next_heartbeat: Duration::ZERO,
            reported_fault: None,
            pdos: Pdos::default(),
            srdos,
            variant: variant.map(str::to_owned),
            lss,
            silent: false,
        }
    }

    /// Starts at bit rate `bits` (bit/s) as far as LSS tells (inquiries and configuration);
    /// 1 Mbit/s otherwise.
    pub fn lss_bit_rate(mut self, bits: u32) -> Self {
        let node = self.config.node.0;
        let sim = &self.sim;
        self.lss = sim.with(|drive| super::lss::slave(drive.store(), node, bits));
        self
    }

    /// Starts without a node id (LSS "not configured", FFh), as a drive out of the box may:
    /// silent until an LSS master gives it one. No effect unless the drive is an LSS slave.
    pub fn lss_unconfigured(mut self) -> Self {
        if let Some(lss) = &self.lss {
            let (address, timing) = (lss.address(), lss.bit_timing());
            self.lss = Some(LssSlave::new(address, UNCONFIGURED, timing));
            self.silent = true;
        }
        self
    }

    /// The node's LSS slave, if the drive is one.
    pub fn lss(&self) -> Option<&LssSlave> {
        self.lss.as_ref()
    }

    /// The node id it communicates at; `None` while LSS left it without one.
    pub fn node_id(&self) -> Option<NodeId> {
        (!self.silent).then_some(self.config.node)
    }

    /// Power off and on: the drive restarts from its stored values and LSS from its stored node
    /// id; returns the boot-up, if the node has a node id.
    pub fn power_cycle(&mut self, now: Duration) -> Option<CanFrame> {
        self.sim.with(|drive| drive.reboot());
        if let Some(id) = self.lss.as_mut().map(LssSlave::power_cycle) {
            self.renumber(id);
        }
        self.boot(now)
    }

    /// Takes node id `id` (FFh: none): the SDO server and SRDOs move to it.
    fn renumber(&mut self, id: u8) {
        let Some(node) = NodeId::new(id) else {
            self.silent = true;
            self.state = NmtState::Initializing;
            return;
        };
        self.silent = false;
        if node == self.config.node {
            return;
        }
        self.config.node = node;
        let sim = self.sim.clone();
        sim.with(|drive| drive.at_node(node.0));
        let dictionary = sim.with(|drive| {
            Dictionary::new(sim.clone(), drive.store().device(), self.variant.as_deref())
        });
        self.sdo = SdoServer::new(node, dictionary);
        self.srdos = sim.with(|drive| Srdos::new(drive.store(), node));
    }

    /// The NMT state.
    pub fn state(&self) -> NmtState {
        self.state
    }

    /// Ends initialisation: the boot-up message, then PRE-OPERATIONAL. A node without a node id
    /// stays silent (`None`).
    pub fn boot(&mut self, now: Duration) -> Option<CanFrame> {
        if self.silent {
            return None;
        }
        self.state = NmtState::PreOperational;
        self.next_heartbeat = now;
        Some(heartbeat_frame(self.config.node, NmtState::Initializing))
    }

    /// Handles a received frame at time `now`; returns the frames to send.
    pub fn handle(&mut self, frame: &CanFrame, now: Duration) -> Vec<CanFrame> {
        if let Some(lss) = &mut self.lss {
            if frame.id() == drivebus::canopen::lss::MASTER_COB {
                let (answer, event) = lss.handle(frame);
                let mut out: Vec<CanFrame> = answer.into_iter().collect();
                if let Some(SlaveEvent::NodeIdAssigned(id)) = event {
                    self.renumber(id);
                    out.extend(self.boot(now));
                }
                return out;
            }
        }
        if self.silent {
            return Vec::new();
        }
        if let Some((command, target)) = NmtCommand::decode(frame) {
            if target.is_none_or(|t| t == self.config.node) {
                return self.nmt(command, now);
            }
            return Vec::new();
        }
        if self.state == NmtState::Operational {
            let (pdos, srdos) = (&mut self.pdos, &mut self.srdos);
            if let Some(sent) = self.sim.with(|drive| pdos.handle(frame, now, drive)) {
                return sent;
            }
            if self.sim.with(|drive| srdos.handle(frame, now, drive)) {
                return Vec::new();
            }
        }
        if frame.id() == cob::SDO_RX + u16::from(self.config.node.0)
            && self.state != NmtState::Stopped
        {
            let answer = self.sdo.handle(frame);
            if self.state == NmtState::Operational && writes_pdo_object(frame) {
                // As on a drive, a PDO whose configuration changes while Operational (disabled,
                // remapped, enabled again) takes the change at once, not at the next start.
                let pdos = &mut self.pdos;
                self.sim.with(|drive| pdos.configure(drive.store()));
            }
            return answer;
        }
        Vec::new()
    }

    fn nmt(&mut self, command: NmtCommand, now: Duration) -> Vec<CanFrame> {
        match command {
            NmtCommand::ResetNode => {
                self.sim.with(|drive| drive.reboot());
                self.lss_reset();
                self.boot(now).into_iter().collect()
            }
            NmtCommand::ResetCommunication => {
                self.lss_reset();
                self.boot(now).into_iter().collect()
            }
            other => {
                let target = other.target_state();
                if target == NmtState::Operational && self.state != NmtState::Operational {
                    if !self.safety_configuration_holds() {
                        return Vec::new();
                    }
                    self.start_srdos(now);
                    let pdos = &mut self.pdos;
                    self.sim.with(|drive| pdos.configure(drive.store()));
                }
                self.state = target;
                Vec::new()
            }
        }
    }

    /// An NMT reset activates the node id LSS configured (CiA 305).
    fn lss_reset(&mut self) {
        if let Some(id) = self.lss.as_mut().map(LssSlave::reset_communication) {
            self.renumber(id);
        }
    }

    /// The heartbeat period: 1017h if described, else the configured one.
    fn heartbeat_period(&self) -> Option<Duration> {
        let described = self.sim.with(|drive| {
            let store = drive.store();
            object(store, 0x1017, 0).and_then(|id| store.int(id))
        });
        match described {
            Some(ms) if ms > 0 => Some(Duration::from_millis(ms as u64)),
            Some(_) => None,
            None => self.config.heartbeat,
        }
    }

    /// An EMCY when the drive's fault changed: its code when one is raised, 0x0000 (error
    /// reset) when it is cleared. Not sent while STOPPED or before boot-up.
    pub fn poll_emcy(&mut self) -> Option<CanFrame> {
        let fault = self.sim.with(|drive| drive.fault());
        if fault == self.reported_fault
            || self.silent
            || matches!(self.state, NmtState::Stopped | NmtState::Initializing)
        {
            return None;
        }
        self.reported_fault = fault;
        let register = if fault.is_some() {
            ErrorRegister::GENERIC
        } else {
            ErrorRegister::empty()
        };
        let emcy = Emcy {
            node: self.config.node,
            code: fault.unwrap_or(0),
            register,
            manufacturer: [0; 5],
        };
        Some(emcy.encode())
    }

    /// Frames due at time `now` (heartbeats).
    pub fn poll(&mut self, now: Duration) -> Option<CanFrame> {
        let period = self.heartbeat_period()?;
        if self.silent || self.state == NmtState::Initializing || now < self.next_heartbeat {
            return None;
        }
        self.next_heartbeat = now + period;
        Some(heartbeat_frame(self.config.node, self.state))
    }

    /// Whether the safety configuration lets the node enter Operational (signatures and 13FEh,
    /// SWD manual line 3568: "A signature error prevents the transition to the operational NMT
    /// state").
    fn safety_configuration_holds(&self) -> bool {
        let node = self.config.node;
        self.sim
            .with(|drive| Srdos::configuration_error(drive.store(), node))
            .is_none()
    }

    /// The SRDOs as the drive is now configured, SCT monitoring from `now`.
    fn start_srdos(&mut self, now: Duration) {
        let (srdos, node) = (&mut self.srdos, self.config.node);
        self.sim.with(|drive| srdos.configure(drive.store(), node));
        self.srdos.start(now);
    }

    /// The SRDO pairs due at `now` (Operational only), after checking the RX SRDOs' timers.
    pub fn poll_srdo(&mut self, now: Duration) -> Vec<CanFrame> {
        if self.state != NmtState::Operational {
            return Vec::new();
        }
        let srdos = &mut self.srdos;
        self.sim.with(|drive| srdos.poll(now, drive.store()))
    }

    /// The event-driven TPDOs due at `now` (Operational only).
    pub fn poll_pdo(&mut self, now: Duration) -> Vec<CanFrame> {
        if self.state != NmtState::Operational {
            return Vec::new();
        }
        let pdos = &mut self.pdos;
        self.sim.with(|drive| pdos.poll(now, drive.store()))
    }

    /// The node's PDOs: the ones it cannot carry, RPDOs too short for their mapping.
    pub fn pdos(&self) -> &Pdos {
        &self.pdos
    }

    /// The node's SRDOs: refusals and the SRDOs it cannot carry.
    pub fn srdos(&self) -> &Srdos {
        &self.srdos
    }

    /// Runs the node on `bus` until the bus fails (e.g. the candump stream ends).
    pub fn run<B: CanBus>(&mut self, bus: &mut B) -> Result<(), BusError> {
        self.run_while(bus, || true)
    }

    /// Runs the node on `bus` while `keep_running` says so (checked every 10 ms).
    pub fn run_while<B: CanBus>(
        &mut self,
        bus: &mut B,
        keep_running: impl Fn() -> bool,
    ) -> Result<(), BusError> {
        super::nodes::run_while(std::slice::from_mut(self), bus, keep_running)
    }

    /// One turn at time `now`: the answers to `received` (if a frame came), then the EMCY,
    /// heartbeat, TPDO and SRDO frames that are due.
    pub fn step(&mut self, received: Option<&CanFrame>, now: Duration) -> Vec<CanFrame> {
        let mut out = received.map_or_else(Vec::new, |frame| self.handle(frame, now));
        out.extend(self.poll_emcy());
        out.extend(self.poll(now));
        out.extend(self.poll_pdo(now));
        out.extend(self.poll_srdo(now));
        out
    }
}

/// Whether `frame` is an SDO request that starts a download (expedited or not) to a PDO
/// communication or mapping object (1400h-1BFFh).
fn writes_pdo_object(frame: &CanFrame) -> bool {
    const INITIATE_DOWNLOAD: u8 = 1;
    match frame.data() {
        [command, lo, hi, ..] if command >> 5 == INITIATE_DOWNLOAD => {
            (0x1400..0x1C00).contains(&u16::from_le_bytes([*lo, *hi]))
        }
        _ => false,
    }
}

//! A CANopen node: boot-up, NMT state, heartbeat producer, the SDO server and the SRDOs, sans-I/O,
//! plus a blocking loop over any CAN backend.

use std::time::Duration;

use drivebus::canopen::emcy::{Emcy, ErrorRegister};
use drivebus::canopen::frame::cob;
use drivebus::canopen::nmt::{heartbeat_frame, NmtCommand, NmtState};
use drivebus::canopen::sdo::server::SdoServer;
use drivebus::canopen::{CanBus, CanFrame, NodeId};
use drivebus::BusError;

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
    srdos: Srdos,
}

impl Node {
    /// A node serving `sim`'s drive; it is INITIALISING until [`Node::boot`]. Node-relative
    /// defaults take their value on `config.node`.
    pub fn new(sim: Simulator, config: NodeConfig, variant: Option<&str>) -> Self {
        sim.with(|drive| drive.at_node(config.node.0));
        let dictionary =
            sim.with(|drive| Dictionary::new(sim.clone(), drive.store().device(), variant));
        let srdos = sim.with(|drive| Srdos::new(drive.store(), config.node));
        Self {
            config,
            sim,
            sdo: SdoServer::new(config.node, dictionary),
            state: NmtState::Initializing,
            next_heartbeat: Duration::ZERO,
            reported_fault: None,
            srdos,
        }
    }

    /// The NMT state.
    pub fn state(&self) -> NmtState {
        self.state
    }

    /// Ends initialisation: the boot-up message, then PRE-OPERATIONAL.
    pub fn boot(&mut self, now: Duration) -> CanFrame {
        self.state = NmtState::PreOperational;
        self.next_heartbeat = now;
        heartbeat_frame(self.config.node, NmtState::Initializing)
    }

    /// Handles a received frame at time `now`; returns the frames to send.
    pub fn handle(&mut self, frame: &CanFrame, now: Duration) -> Vec<CanFrame> {
        if let Some((command, target)) = NmtCommand::decode(frame) {
            if target.is_none_or(|t| t == self.config.node) {
                return self.nmt(command, now);
            }
            return Vec::new();
        }
        if self.state == NmtState::Operational {
            let srdos = &mut self.srdos;
            if self.sim.with(|drive| srdos.handle(frame, now, drive)) {
                return Vec::new();
            }
        }
        if frame.id() == cob::SDO_RX + u16::from(self.config.node.0)
            && self.state != NmtState::Stopped
        {
            return self.sdo.handle(frame);
        }
        Vec::new()
    }

    fn nmt(&mut self, command: NmtCommand, now: Duration) -> Vec<CanFrame> {
        match command {
            NmtCommand::ResetNode => {
                self.sim.with(|drive| drive.reboot());
                vec![self.boot(now)]
            }
            NmtCommand::ResetCommunication => vec![self.boot(now)],
            other => {
                let target = other.target_state();
                if target == NmtState::Operational && self.state != NmtState::Operational {
                    if !self.safety_configuration_holds() {
                        return Vec::new();
                    }
                    self.start_srdos(now);
                }
                self.state = target;
                Vec::new()
            }
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
        if self.state == NmtState::Initializing || now < self.next_heartbeat {
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
    /// heartbeat and SRDO frames that are due.
    pub fn step(&mut self, received: Option<&CanFrame>, now: Duration) -> Vec<CanFrame> {
        let mut out = received.map_or_else(Vec::new, |frame| self.handle(frame, now));
        out.extend(self.poll_emcy());
        out.extend(self.poll(now));
        out.extend(self.poll_srdo(now));
        out
    }
}

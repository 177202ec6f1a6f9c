//! What the simulated drive does besides storing values: state machines, command registers and a
//! motor. Each behaviour is chosen from the description (by the parameters and objects it has)
//! and reacts to writes and to the passing of time through the [`Behaviour`] trait.

use std::fmt::Debug;
use std::time::Duration;

use drivegen::ir::SpeedPhase;

use crate::refusal::Refusal;
use crate::store::{ParamId, Store};

pub mod axis;
pub mod bounds;
pub mod cia402;
pub mod commands;
pub mod communication_loss;
pub mod motor;
pub mod ramp;
pub mod s_curve;
pub mod srdo_validity;
pub mod state_machine;
pub mod torque;
pub mod trajectory;
pub mod write_lock;

/// What the power stage is doing, as the active state machine commands it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Motion {
    /// Power stage off: the motor does not follow any setpoint.
    #[default]
    Disabled,
    /// Following the speed setpoint held in this parameter.
    Following(ParamId),
    /// Stopping at once (quick stop, stop with maximum torque, fault).
    QuickStop,
    /// Ramping to zero along the deceleration ramp of the setpoint held in this parameter.
    RampStop(ParamId),
    /// Ramping to zero from the setpoint held in the first parameter at the deceleration held
    /// in the second (the quick stop deceleration 6085h), in the units of the setpoint's ramp.
    RampStopAt(ParamId, ParamId),
}

/// A stop the drive makes on its own, not commanded through a state machine (the serial
/// watchdog's `coast` and `quick_stop` actions).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Halt {
    /// The power stage turns off; the motor coasts.
    Coast,
    /// The drive stops as its quick stop does.
    QuickStop,
}

/// State behaviours share.
#[derive(Debug, Clone, Default)]
pub struct Shared {
    /// What the motor does.
    pub motion: Motion,
    /// An active fault code, injected by a test or raised by the drive.
    pub fault: Option<u16>,
    /// Set by a reset command: the drive reboots after the current request.
    pub reset_requested: bool,
    /// A stop the drive made on its own during this tick, for the state machine to show.
    pub halt: Option<Halt>,
    /// Where the motor's speed is relative to its target while the power stage drives it (set
    /// by the motor; `None` while it is off).
    pub phase: Option<SpeedPhase>,
    /// The mode-specific statusword bits 10, 12 and 13 the axis shows (profile position,
    /// homing), added to the CiA 402 statusword.
    pub mode_bits: u16,
    /// Set by a test: the load does not move, so the following error grows.
    pub load_blocked: bool,
    /// Where the simulated home switch is.
    pub home_switch: HomeSwitch,
    /// In profile torque mode: the torque demand stands on the target torque (set by the
    /// torque load, shown by the axis as statusword bit 10).
    pub torque_reached: bool,
}

/// Where the simulated home switch is, in position units as the drive counts them now; `None`:
/// the axis has none, and homing on a switch fails.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HomeSwitch(pub Option<f64>);

impl HomeSwitch {
    /// Where a drive has its home switch at power-on: some way on the negative side, so that a
    /// homing run is seen to move.
    pub const AT_POWER_ON: f64 = -12_000.0;

    /// The drive's positions moved by `by` (homing set a new zero): the switch stays where it
    /// is physically.
    pub fn shift(&mut self, by: f64) {
        if let Some(at) = &mut self.0 {
            *at += by;
        }
    }
}

impl Default for HomeSwitch {
    fn default() -> Self {
        HomeSwitch(Some(Self::AT_POWER_ON))
    }
}

/// One aspect of the drive's behaviour.
pub trait Behaviour: Debug + Send {
    /// Refuses a write the drive does not accept in its present state (checked after range).
    fn accept(&self, _store: &Store, _id: ParamId, _bytes: &[u8]) -> Result<(), Refusal> {
        Ok(())
    }
    /// Reacts to a value a client wrote (already stored).
    fn written(&mut self, _store: &mut Store, _shared: &mut Shared, _id: ParamId) {}
    /// Advances the drive by `dt`.
    fn tick(&mut self, _store: &mut Store, _shared: &mut Shared, _dt: Duration) {}
    /// Returns to the power-on state after a reboot (values already reloaded).
    fn reset(&mut self, _store: &mut Store, _shared: &mut Shared) {}
    /// The drive received a request (any valid communication feeds a watchdog).
    fn heard(&mut self) {}
    /// Shows what the other behaviours did, after every behaviour has reacted to a write, a
    /// tick or a reset (a status that depends on the motor's speed).
    fn settle(&mut self, _store: &mut Store, _shared: &mut Shared) {}
}

/// The behaviours a description calls for, in the order they run: the write lock, bounds set by
/// other parameters, commands, the communication loss supervision, state machines, the motor,
/// the positioning axis, the SRDO configuration-valid flag.
pub fn for_device(store: &mut Store) -> Vec<Box<dyn Behaviour>> {
    let mut behaviours: Vec<Box<dyn Behaviour>> = Vec::new();
    if let Some(b) = write_lock::WriteLock::detect(store) {
        behaviours.push(Box::new(b));
    }
    if let Some(b) = bounds::Bounds::detect(store) {
        behaviours.push(Box::new(b));
    }
    if let Some(b) = commands::Commands::detect(store) {
        behaviours.push(Box::new(b));
    }
    if let Some(b) = communication_loss::CommunicationLoss::detect(store) {
        behaviours.push(Box::new(b));
    }
    if let Some(b) = state_machine::DescribedMachine::detect(store) {
        behaviours.push(Box::new(b));
    }
    if let Some(b) = cia402::Cia402::detect(store) {
        behaviours.push(Box::new(b));
    }
    if let Some(b) = motor::Motor::detect(store) {
        behaviours.push(Box::new(b));
    }
    // After the motor: in profile torque the load's speed replaces the motor's.
    if let Some(b) = torque::TorqueLoad::detect(store) {
        behaviours.push(Box::new(b));
    }
    // After the motor: in the positioning modes the axis shows the speed, in the others it
    // integrates the motor's.
    if let Some(b) = axis::Axis::detect(store) {
        behaviours.push(Box::new(b));
    }
    if let Some(b) = srdo_validity::SrdoValidity::detect(store) {
        behaviours.push(Box::new(b));
    }
    behaviours
}

/// The parameter at CANopen `index:subindex`, if the description has one.
pub(crate) fn object(store: &Store, index: u16, subindex: u8) -> Option<ParamId> {
    store.device().parameters.iter().position(|p| {
        p.canopen
            .iter()
            .any(|a| a.index == index && a.subindex == subindex)
    })
}

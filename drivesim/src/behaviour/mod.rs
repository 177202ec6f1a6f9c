//! What the simulated drive does besides storing values: state machines, command registers and a
//! motor. Each behaviour is chosen from the description (by the parameters and objects it has)
//! and reacts to writes and to the passing of time through the [`Behaviour`] trait.

use std::fmt::Debug;
use std::time::Duration;

use drivegen::ir::SpeedPhase;

use crate::refusal::Refusal;
use crate::store::{ParamId, Store};

pub mod bounds;
pub mod cia402;
pub mod commands;
pub mod communication_loss;
pub mod motor;
pub mod ramp;
pub mod srdo_validity;
pub mod state_machine;
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
/// other parameters, commands, the communication loss supervision, state machines, the motor, the SRDO configuration-valid flag.
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

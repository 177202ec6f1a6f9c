//! A vendor state machine run from the description's `[state_machine]`, `[[state]]` and
//! `[[transition]]` tables, with no per-drive code: the drive powers up in the `initial` state
//! and follows its automatic transitions; writing a command value takes the command transition
//! that leaves the current state with that value (other values change nothing); an injected
//! fault enters the `fault` state and shows its code in `fault_code`; a reset powers up again.
//! The status parameter shows the entered state's pattern (the first whose `when` holds, else
//! the first without one), and the state's `motion` tells the motor what to do. A `when`
//! parameter whose writes take effect only after a reset counts with its power-on value; a
//! pattern with a `speed` phase shows while the motor's speed is in it (ACCEL, DECEL, RUN).
//!
//! A `command` that is one of several commands sharing a register (Lenze smd #1: one bit per
//! command) stands for the register: writing any of those commands is writing its trigger value.
//! A stop the drive makes on its own (the watchdog's coast or quick stop) enters the `coast` or
//! `quick_stop` state when the machine names one.
//!
//! States and transitions are walked on the model's table (`Machine::state_index`,
//! `Machine::taken`) as the IR lends it (`StateMachine::with_view`): the same table a drive
//! crate holds as `MACHINE` and its handle plans with. What this file adds is the drive's side
//! the table leaves out: which pattern it shows, what the motor does, faults and resets.

use std::collections::HashMap;
use std::time::Duration;

use drivebus::control::TransitionKind as Cause;
use drivegen::ir::{self, Effect, Motion as StateMotion, SpeedPhase, StatusPattern, Table};

use super::{Behaviour, Halt, Motion, Shared};
use crate::store::{ParamId, Store};

/// Most automatic transitions followed after one event: a table whose automatic transitions
/// form a cycle must not hang the simulator.
const MAX_AUTOMATIC_HOPS: usize = 32;

/// The description's state machine and the state the simulated drive is in.
#[derive(Debug)]
pub struct DescribedMachine {
    machine: ir::StateMachine,
    status: ParamId,
    command: ParamId,
    setpoint: Option<ParamId>,
    fault_code: Option<ParamId>,
    /// The commands sharing `command`'s register and the value each writes there (empty when
    /// `command` is a plain register).
    commands: Vec<(ParamId, i128)>,
    /// Power-on values of the `when` parameters that take effect only after a reset.
    latched: HashMap<ParamId, i128>,
    /// The motor's speed phase, as last shown.
    phase: Option<SpeedPhase>,
    state: usize,
}

impl DescribedMachine {
    /// Present when the description has a `[state_machine]` whose registers exist; starts in
    /// the power-on state.
    pub fn detect(store: &mut Store) -> Option<Self> {
        let machine = store.device().state_machine.clone()?;
        let id = |name: &Option<String>| name.as_deref().and_then(|n| store.id(n));
        let mut described = Self {
            status: store.id(&machine.status)?,
            command: store.id(&machine.command)?,
            setpoint: id(&machine.setpoint),
            fault_code: id(&machine.fault_code),
            commands: Vec::new(),
            latched: HashMap::new(),
            phase: None,
            state: 0,
            machine,
        };
        described.commands = described.register_commands(store);
        described.power_on(store);
        Some(described)
    }

    /// The command parameters written at the command parameter's holding registers, with their
    /// trigger values, when the command parameter is itself such a command.
    fn register_commands(&self, store: &Store) -> Vec<(ParamId, i128)> {
        let device = store.device();
        let command = store.parameter(self.command);
        let trigger = |p: &ir::Parameter| p.command.as_ref().and_then(|c| c.value);
        if trigger(command).is_none() {
            return Vec::new();
        }
        let registers: Vec<u16> = command
            .modbus
            .iter()
            .filter(|a| a.table == Table::Holding)
            .map(|a| a.address)
            .collect();
        device
            .parameters
            .iter()
            .enumerate()
            .filter(|(_, p)| {
                p.modbus
                    .iter()
                    .any(|a| a.table == Table::Holding && registers.contains(&a.address))
            })
            .filter_map(|(id, p)| Some((id, i128::from(trigger(p)?))))
            .collect()
    }

    /// The value a write of `id` puts in the command register, if it is a command.
    fn command_value(&self, store: &Store, id: ParamId) -> Option<i128> {
        if self.commands.is_empty() {
            return (id == self.command).then(|| store.int(id).unwrap_or(0));
        }
        self.commands
            .iter()
            .find(|(c, _)| *c == id)
            .map(|&(_, value)| value)
    }

    /// The index of state `name`, from the model's table.
    fn index(&self, name: &str) -> Option<usize> {
        self.machine
            .with_view(|m| m.state_index(name))
            .map(usize::from)
    }

    /// The state the current state leads to on `cause`, by the model's table.
    fn taken(&self, cause: Cause) -> Option<usize> {
        let from = u8::try_from(self.state).ok()?;
        self.machine
            .with_view(|m| m.taken(from, cause).map(|t| t.to))
            .map(usize::from)
    }

    fn current(&self) -> &ir::MachineState {
        &self.machine.states[self.state]
    }

    fn power_on(&mut self, store: &mut Store) {
        self.latch(store);
        let initial = self.index(&self.machine.initial).unwrap_or(0);
        self.enter(store, initial);
    }

    /// Keeps the power-on value of every `when` parameter whose writes wait for a reset.
    fn latch(&mut self, store: &Store) {
        let conditions = self.machine.states.iter().flat_map(|s| &s.status);
        let delayed = conditions
            .filter_map(|p| store.id(&p.when.as_ref()?.parameter))
            .filter(|&id| store.parameter(id).effect != Effect::Immediate);
        self.latched = delayed
            .filter_map(|id| Some((id, store.int(id)?)))
            .collect();
    }

    /// Enters `state`, shows it, and follows the automatic transitions out of it.
    fn enter(&mut self, store: &mut Store, state: usize) {
        self.state = state;
        for _ in 0..MAX_AUTOMATIC_HOPS {
            match self.taken(Cause::Automatic) {
                Some(next) => self.state = next,
                None => break,
            }
        }
        self.show(store);
    }

    fn shown_pattern(&self, store: &Store) -> Option<&StatusPattern> {
        let effective = |id| self.latched.get(&id).copied().or_else(|| store.int(id));
        let holds = |c: &ir::Condition| {
            store
                .id(&c.parameter)
                .and_then(effective)
                .is_some_and(|raw| raw == i128::from(c.value))
        };
        let conditional = |p: &&StatusPattern| p.when.is_some() || p.speed.is_some();
        let shows = |p: &&StatusPattern| {
            p.when.as_ref().is_none_or(holds)
                && p.speed.is_none_or(|phase| self.phase == Some(phase))
        };
        let patterns = &self.current().status;
        patterns
            .iter()
            .find(|p| conditional(p) && shows(p))
            .or_else(|| patterns.iter().find(|p| !conditional(p)))
    }

    /// Shows the current state's pattern in the status parameter.
    fn show(&self, store: &mut Store) {
        let pattern = self.shown_pattern(store);
        store.set_int(self.status, pattern.map_or(0, |p| i128::from(p.value)));
    }

    fn motion(&self) -> Motion {
        match (self.current().motion, self.setpoint) {
            (StateMotion::Follow, Some(setpoint)) => Motion::Following(setpoint),
            (StateMotion::RampStop, Some(setpoint)) => Motion::RampStop(setpoint),
            (StateMotion::QuickStop | StateMotion::RampStop, _) => Motion::QuickStop,
            _ => Motion::Disabled,
        }
    }

    /// The state a stop the drive made on its own leads to, if the machine names one.
    fn halt_state(&self, halt: Halt) -> Option<usize> {
        let name = match halt {
            Halt::Coast => self.machine.coast.as_deref(),
            Halt::QuickStop => self.machine.quick_stop.as_deref(),
        };
        name.and_then(|n| self.index(n))
    }

    fn fault_state(&self) -> Option<usize> {
        self.machine.fault.as_deref().and_then(|f| self.index(f))
    }
}

impl Behaviour for DescribedMachine {
    fn written(&mut self, store: &mut Store, shared: &mut Shared, id: ParamId) {
        let Some(word) = self.command_value(store, id) else {
            return;
        };
        let next = u16::try_from(word)
            .ok()
            .and_then(|word| self.taken(Cause::Command(word)));
        if let Some(next) = next {
            self.enter(store, next);
        }
        shared.motion = self.motion();
    }

    /// A fault injected into the drive enters the fault state and shows its code; a stop the
    /// drive made on its own enters the state the machine names for it.
    fn tick(&mut self, store: &mut Store, shared: &mut Shared, _dt: Duration) {
        if let Some(state) = shared.halt.and_then(|h| self.halt_state(h)) {
            shared.halt = None;
            self.enter(store, state);
            shared.motion = self.motion();
        }
        let (Some(code), Some(fault)) = (shared.fault, self.fault_state()) else {
            return;
        };
        if self.state != fault {
            self.enter(store, fault);
            if let Some(id) = self.fault_code {
                store.set_int(id, i128::from(code));
            }
            shared.motion = self.motion();
        }
    }

    /// Shows the pattern of the motor's present speed phase, in a state whose patterns depend on
    /// it (other states keep what they showed on entry).
    fn settle(&mut self, store: &mut Store, shared: &mut Shared) {
        self.phase = shared.phase;
        if self.current().status.iter().any(|p| p.speed.is_some()) {
            self.show(store);
        }
    }

    /// A reset clears the fault; the drive powers up again.
    fn reset(&mut self, store: &mut Store, shared: &mut Shared) {
        shared.fault = None;
        self.power_on(store);
        shared.motion = self.motion();
    }
}

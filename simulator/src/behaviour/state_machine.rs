//! A vendor state machine run from the description's `[state_machine]`, `[[state]]` and
//! `[[transition]]` tables, with no per-drive code: the drive powers up in the `initial` state
//! and follows its automatic transitions; writing a command value takes the command transition
//! that leaves the current state with that value (other values change nothing); an injected
//! fault enters the `fault` state and shows its code in `fault_code`; a reset powers up again.
//! The status parameter shows the entered state's pattern (the first whose `when` holds, else
//! the first without one), and the state's `motion` tells the motor what to do. A `when`
//! parameter whose writes take effect only after a reset counts with its power-on value.

use std::collections::HashMap;
use std::time::Duration;

use drivegen::ir::{self, Effect, Motion as StateMotion, StatusPattern, TransitionKind};

use super::{Behaviour, Motion, Shared};
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
    /// Power-on values of the `when` parameters that take effect only after a reset.
    latched: HashMap<ParamId, i128>,
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
            latched: HashMap::new(),
            state: 0,
            machine,
        };
        described.power_on(store);
        Some(described)
    }

    fn index(&self, name: &str) -> Option<usize> {
        self.machine.states.iter().position(|s| s.name == name)
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
            let next = self
                .leaving(|t| t.kind == TransitionKind::Automatic)
                .and_then(|t| self.index(&t.to));
            match next {
                Some(next) => self.state = next,
                None => break,
            }
        }
        let pattern = self.shown_pattern(store);
        store.set_int(self.status, pattern.map_or(0, |p| i128::from(p.value)));
    }

    /// The first transition out of the current state that `wanted` accepts.
    fn leaving(&self, wanted: impl Fn(&ir::Transition) -> bool) -> Option<&ir::Transition> {
        let name = &self.current().name;
        self.machine
            .transitions
            .iter()
            .find(|t| t.from.contains(name) && wanted(t))
    }

    fn shown_pattern(&self, store: &Store) -> Option<&StatusPattern> {
        let effective = |id| self.latched.get(&id).copied().or_else(|| store.int(id));
        let holds = |c: &ir::Condition| {
            store
                .id(&c.parameter)
                .and_then(effective)
                .is_some_and(|raw| raw == i128::from(c.value))
        };
        let patterns = &self.current().status;
        patterns
            .iter()
            .find(|p| p.when.as_ref().is_some_and(holds))
            .or_else(|| patterns.iter().find(|p| p.when.is_none()))
    }

    fn motion(&self) -> Motion {
        match (self.current().motion, self.setpoint) {
            (StateMotion::Follow, Some(setpoint)) => Motion::Following(setpoint),
            (StateMotion::QuickStop, _) => Motion::QuickStop,
            _ => Motion::Disabled,
        }
    }

    fn fault_state(&self) -> Option<usize> {
        self.machine.fault.as_deref().and_then(|f| self.index(f))
    }
}

impl Behaviour for DescribedMachine {
    fn written(&mut self, store: &mut Store, shared: &mut Shared, id: ParamId) {
        if id != self.command {
            return;
        }
        let word = store.int(id).unwrap_or(0);
        let commanded = |t: &ir::Transition| {
            t.kind == TransitionKind::Command && t.command.map(i128::from) == Some(word)
        };
        if let Some(next) = self.leaving(commanded).and_then(|t| self.index(&t.to)) {
            self.enter(store, next);
        }
        shared.motion = self.motion();
    }

    /// A fault injected into the drive enters the fault state and shows its code.
    fn tick(&mut self, store: &mut Store, shared: &mut Shared, _dt: Duration) {
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

    /// A reset clears the fault; the drive powers up again.
    fn reset(&mut self, store: &mut Store, shared: &mut Shared) {
        shared.fault = None;
        self.power_on(store);
        shared.motion = self.motion();
    }
}

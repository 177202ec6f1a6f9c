//! The IR lends its vendor state machine as the model's [`Machine`]: the table generated code
//! holds as `MACHINE` and the simulator walks, built from the description's states and
//! transitions in one place.
//!
//! `Machine<'a>` borrows nested slices (`&'a [StateDef<'a>]`, each with `&'a [StatePattern]`),
//! which an owned IR cannot hand out without keeping references into itself. The view is built
//! for the length of a closure instead: the caller gets `&Machine<'_>` and nothing outlives the
//! call (no self-reference, no leak).

use drivebus_model::control::{
    Machine, StateDef, StatePattern, TransitionDef, TransitionKind as Cause,
};

use super::{StateMachine, TransitionKind};

impl StateMachine {
    /// Runs `f` with the machine as the model's table: the states in recognition order with their
    /// patterns (a pattern's `when` and `speed` say when a drive shows it, which recognition does
    /// not need), and one transition per state a transition leaves. A command transition
    /// without a value is external, and a state name not in the table is index 0 (validation
    /// refuses both before anything is generated).
    pub fn with_view<R>(&self, f: impl FnOnce(&Machine<'_>) -> R) -> R {
        let patterns: Vec<Vec<StatePattern>> = self
            .states
            .iter()
            .map(|s| {
                s.status
                    .iter()
                    .map(|p| StatePattern {
                        mask: p.mask,
                        value: p.value,
                    })
                    .collect()
            })
            .collect();
        let states: Vec<StateDef<'_>> = self
            .states
            .iter()
            .zip(&patterns)
            .map(|(s, patterns)| StateDef {
                name: &s.name,
                patterns,
            })
            .collect();
        let transitions: Vec<TransitionDef<'_>> = self.transition_defs().collect();
        f(&Machine {
            states: &states,
            transitions: &transitions,
        })
    }

    /// Each transition once per state it leaves, in description order.
    fn transition_defs(&self) -> impl Iterator<Item = TransitionDef<'_>> {
        self.transitions.iter().flat_map(move |t| {
            let kind = match (t.kind, t.command) {
                (TransitionKind::Command, Some(value)) => Cause::Command(value),
                (TransitionKind::Automatic, _) => Cause::Automatic,
                _ => Cause::External,
            };
            let to = self.state_index(&t.to);
            let doc = t.doc.as_deref().unwrap_or_default();
            t.from.iter().map(move |from| TransitionDef {
                name: &t.name,
                from: self.state_index(from),
                to,
                kind,
                doc,
            })
        })
    }

    /// The index of state `name` in the table (0 when it is missing).
    fn state_index(&self, name: &str) -> u8 {
        let index = self
            .states
            .iter()
            .position(|s| s.name == name)
            .unwrap_or_default();
        u8::try_from(index).unwrap_or(u8::MAX)
    }
}

#[cfg(test)]
mod tests {
    use drivebus_model::control::TransitionKind as Cause;

    use crate::ir::TransitionKind;

    #[test]
    fn the_view_holds_every_state_and_each_transition_once_per_state_it_leaves() {
        let device = crate::test_support::shipped("lenze-smd");
        let machine = device.state_machine.as_ref().expect("smd has a machine");
        machine.with_view(|view| {
            assert_eq!(view.states.len(), machine.states.len());
            for (i, state) in machine.states.iter().enumerate() {
                assert_eq!(view.state_index(&state.name), u8::try_from(i).ok());
                assert_eq!(view.states[i].patterns.len(), state.status.len());
                for p in &state.status {
                    let recognised = view.recognise(p.value).map(usize::from);
                    assert!(recognised.is_some_and(|r| r <= i), "{}", state.name);
                }
            }
            let hops: usize = machine.transitions.iter().map(|t| t.from.len()).sum();
            assert_eq!(view.transitions.len(), hops);
            for t in &machine.transitions {
                let cause = match (t.kind, t.command) {
                    (TransitionKind::Command, Some(v)) => Cause::Command(v),
                    (TransitionKind::Automatic, _) => Cause::Automatic,
                    _ => Cause::External,
                };
                for from in &t.from {
                    let from = view.state_index(from).expect("a state");
                    let taken = view.taken(from, cause).expect("a transition");
                    assert_eq!(view.states[usize::from(taken.to)].name, t.to);
                }
            }
        });
    }
}

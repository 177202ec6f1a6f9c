//! A drive state machine as data, and the planner that walks it.
//!
//! States are recognised from a status register (first matching state in table order); transitions
//! are caused by writing a command value, happen by themselves, or need an outside event (a safety
//! input, a fault). The planner finds the cheapest path to a target state and answers with its
//! first hop; command and automatic hops cost 1, external hops cost [`EXTERNAL_COST`], so a path
//! through an outside event is chosen only when nothing else reaches the target.

/// Most states a table may hold; the planner keeps one distance per state on the stack.
pub const MAX_STATES: usize = 32;

/// What an external hop costs in the path search: more than any path of commands.
pub const EXTERNAL_COST: u32 = 1_000;

/// One way a state shows in the status register: `status & mask == value`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StatePattern {
    /// Bits that decide.
    pub mask: u16,
    /// Their values in this state.
    pub value: u16,
}

impl StatePattern {
    /// Whether `status` shows this pattern.
    pub const fn matches(&self, status: u16) -> bool {
        status & self.mask == self.value
    }
}

/// A state of the machine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StateDef<'a> {
    /// Name as in the description or the standard.
    pub name: &'a str,
    /// The state is recognised when any of these patterns matches.
    pub patterns: &'a [StatePattern],
}

/// What causes a transition.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TransitionKind {
    /// Writing this value to the command register.
    Command(u16),
    /// The drive moves by itself (initialisation done, fault reaction finished).
    Automatic,
    /// An event outside the master's control (safety input, fault, reset input).
    External,
}

/// A transition between two states.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TransitionDef<'a> {
    /// Name as in the manual (`"T2"`, `"15"`).
    pub name: &'a str,
    /// Index of the state it leaves.
    pub from: u8,
    /// Index of the state it enters.
    pub to: u8,
    /// What causes it.
    pub kind: TransitionKind,
    /// What the manual says about it.
    pub doc: &'a str,
}

/// A state machine: states in recognition order, and transitions.
///
/// Generated code holds `Machine<'static>` constants; a tool that loads a description at run time
/// lends a view of its own tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Machine<'a> {
    /// States; the first one whose pattern matches the status is the current state.
    pub states: &'a [StateDef<'a>],
    /// Transitions.
    pub transitions: &'a [TransitionDef<'a>],
}

/// The planner's answer for one status observation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plan<'a> {
    /// The machine is in the target state.
    Done,
    /// Write the transition's command value.
    Command(&'a TransitionDef<'a>),
    /// The drive leaves this state by itself; poll again.
    Await(&'a TransitionDef<'a>),
    /// Only an outside event leads on (e.g. a reset input); the transition says which.
    NeedsExternal(&'a TransitionDef<'a>),
    /// No sequence of transitions reaches the target.
    Unreachable,
    /// The table has more than [`MAX_STATES`] states or a transition names a missing state.
    BadTable,
}

impl<'a> Machine<'a> {
    /// Index of the state called `name`.
    pub fn state_index(&self, name: &str) -> Option<u8> {
        let index = self.states.iter().position(|s| s.name == name)?;
        u8::try_from(index).ok()
    }

    /// The current state: the first state whose pattern matches `status`.
    pub fn recognise(&self, status: u16) -> Option<u8> {
        let index = self
            .states
            .iter()
            .position(|s| s.patterns.iter().any(|p| p.matches(status)))?;
        u8::try_from(index).ok()
    }

    /// The value to write to go from state `from` straight into state `to`, if one command
    /// transition does it.
    pub fn command_between(&self, from: u8, to: u8) -> Option<u16> {
        self.transitions.iter().find_map(|t| match t.kind {
            TransitionKind::Command(value) if t.from == from && t.to == to => Some(value),
            _ => None,
        })
    }

    /// The states one command transition leads from straight into state `to`.
    pub fn commanded_from(&self, to: u8) -> impl Iterator<Item = &'a StateDef<'a>> + '_ {
        self.transitions
            .iter()
            .filter(move |t| t.to == to && matches!(t.kind, TransitionKind::Command(_)))
            .filter_map(|t| self.states.get(usize::from(t.from)))
    }

    /// The transition a drive in state `from` takes on `cause` (a command value written, or
    /// nothing: `Automatic`): the first in table order that leaves `from` with that cause. A
    /// simulated drive walks the table with it.
    pub fn taken(&self, from: u8, cause: TransitionKind) -> Option<&'a TransitionDef<'a>> {
        let transitions: &'a [TransitionDef<'a>] = self.transitions;
        transitions
            .iter()
            .find(|t| t.from == from && t.kind == cause)
    }

    /// The next hop from state `from` towards state `to`, using only transitions `allowed` accepts.
    pub fn next(&self, from: u8, to: u8, allowed: impl Fn(&TransitionDef) -> bool) -> Plan<'a> {
        if from == to {
            return Plan::Done;
        }
        let Some(distance) = self.distances_to(to, &allowed) else {
            return Plan::BadTable;
        };
        let transitions: &'a [TransitionDef<'a>] = self.transitions;
        let best = transitions
            .iter()
            .filter(|t| t.from == from && allowed(t))
            .filter_map(|t| {
                let rest = distance[usize::from(t.to)];
                (rest != u32::MAX).then(|| (cost(t).saturating_add(rest), t))
            })
            .min_by_key(|(total, _)| *total);
        match best {
            None => Plan::Unreachable,
            Some((_, t)) => match t.kind {
                TransitionKind::Command(_) => Plan::Command(t),
                TransitionKind::Automatic => Plan::Await(t),
                TransitionKind::External => Plan::NeedsExternal(t),
            },
        }
    }

    /// Cost of the cheapest path from every state to `target` (`u32::MAX`: none); `None` if the
    /// table is malformed.
    fn distances_to(
        &self,
        target: u8,
        allowed: &impl Fn(&TransitionDef) -> bool,
    ) -> Option<[u32; MAX_STATES]> {
        let states = self.states.len();
        let in_table = |i: u8| usize::from(i) < states;
        if states > MAX_STATES
            || !in_table(target)
            || self
                .transitions
                .iter()
                .any(|t| !in_table(t.from) || !in_table(t.to))
        {
            return None;
        }
        let mut distance = [u32::MAX; MAX_STATES];
        distance[usize::from(target)] = 0;
        // Bellman-Ford: at most `states` rounds of relaxation, stopping early once nothing changes.
        for _ in 0..states {
            let mut changed = false;
            for t in self.transitions.iter().filter(|t| allowed(t)) {
                let via = distance[usize::from(t.to)];
                if via == u32::MAX {
                    continue;
                }
                let total = via.saturating_add(cost(t));
                let slot = &mut distance[usize::from(t.from)];
                if total < *slot {
                    *slot = total;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        Some(distance)
    }
}

fn cost(transition: &TransitionDef) -> u32 {
    match transition.kind {
        TransitionKind::External => EXTERNAL_COST,
        TransitionKind::Command(_) | TransitionKind::Automatic => 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const fn state(name: &'static str, patterns: &'static [StatePattern]) -> StateDef<'static> {
        StateDef { name, patterns }
    }
    const fn hop(
        name: &'static str,
        from: u8,
        to: u8,
        kind: TransitionKind,
    ) -> TransitionDef<'static> {
        TransitionDef {
            name,
            from,
            to,
            kind,
            doc: "",
        }
    }

    // idle(0) --a:1--> busy(1) --b:auto--> done(2); stuck(3) --c:external--> idle
    const TOY: Machine = Machine {
        states: &[
            state(
                "idle",
                &[StatePattern {
                    mask: 0x3,
                    value: 0x0,
                }],
            ),
            state(
                "busy",
                &[StatePattern {
                    mask: 0x3,
                    value: 0x1,
                }],
            ),
            state(
                "done",
                &[
                    StatePattern {
                        mask: 0x3,
                        value: 0x2,
                    },
                    StatePattern {
                        mask: 0x4,
                        value: 0x4,
                    },
                ],
            ),
            state(
                "stuck",
                &[StatePattern {
                    mask: 0x3,
                    value: 0x3,
                }],
            ),
        ],
        transitions: &[
            hop("a", 0, 1, TransitionKind::Command(1)),
            hop("b", 1, 2, TransitionKind::Automatic),
            hop("c", 3, 0, TransitionKind::External),
            hop("back", 2, 0, TransitionKind::Command(0)),
        ],
    };

    #[test]
    fn recognises_the_first_matching_state_and_any_of_its_patterns() {
        assert_eq!(TOY.recognise(0x0), Some(0));
        assert_eq!(TOY.recognise(0x2), Some(2));
        assert_eq!(
            TOY.recognise(0x5),
            Some(1),
            "busy comes before done's second pattern"
        );
        assert_eq!(TOY.recognise(0x4), Some(0));
        assert_eq!(TOY.state_index("stuck"), Some(3));
        assert_eq!(TOY.state_index("nowhere"), None);
    }

    #[test]
    fn plans_command_then_waits_for_the_automatic_hop() {
        assert!(matches!(TOY.next(0, 2, |_| true), Plan::Command(t) if t.name == "a"));
        assert!(matches!(TOY.next(1, 2, |_| true), Plan::Await(t) if t.name == "b"));
        assert_eq!(TOY.next(2, 2, |_| true), Plan::Done);
    }

    #[test]
    fn one_command_hops_are_found_by_their_ends() {
        assert_eq!(TOY.command_between(0, 1), Some(1));
        assert_eq!(TOY.command_between(2, 0), Some(0));
        assert_eq!(TOY.command_between(1, 2), None, "automatic, not commanded");
        assert_eq!(TOY.command_between(0, 2), None, "two hops");
        let into_idle: std::vec::Vec<&str> = TOY.commanded_from(0).map(|s| s.name).collect();
        assert_eq!(into_idle, ["done"], "stuck leaves by an external hop only");
    }

    #[test]
    fn a_drive_takes_the_first_transition_with_the_cause() {
        assert_eq!(
            TOY.taken(0, TransitionKind::Command(1)).map(|t| t.name),
            Some("a")
        );
        assert_eq!(
            TOY.taken(0, TransitionKind::Command(2)),
            None,
            "no such command"
        );
        assert_eq!(
            TOY.taken(1, TransitionKind::Automatic).map(|t| t.to),
            Some(2)
        );
        assert_eq!(TOY.taken(0, TransitionKind::Automatic), None);
        assert_eq!(
            TOY.taken(3, TransitionKind::External).map(|t| t.to),
            Some(0)
        );
    }

    #[test]
    fn external_hops_are_reported_not_commanded() {
        assert!(matches!(TOY.next(3, 2, |_| true), Plan::NeedsExternal(t) if t.name == "c"));
    }

    #[test]
    fn filtered_transitions_make_targets_unreachable() {
        assert_eq!(TOY.next(0, 2, |t| t.name != "a"), Plan::Unreachable);
        assert_eq!(TOY.next(2, 3, |_| true), Plan::Unreachable);
    }

    #[test]
    fn malformed_tables_are_reported() {
        const BROKEN: Machine = Machine {
            states: &[state("only", &[])],
            transitions: &[hop("x", 0, 7, TransitionKind::Automatic)],
        };
        assert_eq!(BROKEN.next(0, 0, |_| true), Plan::Done);
        assert_eq!(BROKEN.next(0, 1, |_| true), Plan::BadTable);
    }
}

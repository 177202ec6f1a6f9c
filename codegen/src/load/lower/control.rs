//! Lowering of drive control: `[cia402]` quirks and the vendor `[state_machine]` with its
//! `[[state]]` and `[[transition]]` tables.

use drivebus_model::control::Quirk;
use toml::Spanned;

use super::{Lowering, VALUE_RULE};
use crate::diagnostic::Span;
use crate::ir;
use crate::load::raw::*;

impl Lowering<'_> {
    pub(super) fn cia402(&mut self, raw: &Spanned<RawCia402>) -> ir::Cia402 {
        let c = raw.get_ref();
        let mut quirks = Vec::new();
        for quirk in &c.quirks {
            if Quirk::from_name(quirk.get_ref()).is_some() {
                quirks.push(quirk.get_ref().clone());
            } else {
                let span = self.span(quirk);
                let known: Vec<&str> = Quirk::ALL.iter().map(|q| q.name()).collect();
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("unknown CiA 402 quirk `{}`", quirk.get_ref()),
                    format!("known quirks: {}", known.join(", ")),
                );
            }
        }
        let fault_reset_hold_ms = c
            .fault_reset_hold_ms
            .as_ref()
            .and_then(|ms| self.int_in::<u32>(ms, "fault reset hold time"))
            .unwrap_or(0);
        let sto_bit = c.sto_bit.as_ref().and_then(|s| {
            let bit = Spanned::new(s.span(), s.get_ref().bit);
            let bit = self.int_in::<u8>(&bit, "safe torque off bit")?;
            Some(ir::StoBit {
                parameter: s.get_ref().parameter.clone(),
                bit,
            })
        });
        ir::Cia402 {
            quirks,
            fault_reset_hold_ms,
            sto_bit,
            source: c.source.as_ref().and_then(|s| self.citation(s)),
            span: self.span(raw),
        }
    }

    pub(super) fn state_machine(
        &mut self,
        raw: &Spanned<RawStateMachine>,
        states: &[Spanned<RawState>],
        transitions: &[Spanned<RawTransition>],
    ) -> ir::StateMachine {
        let m = raw.get_ref();
        let states: Vec<ir::MachineState> = states.iter().map(|s| self.machine_state(s)).collect();
        let transitions: Vec<ir::Transition> = transitions
            .iter()
            .filter_map(|t| self.transition(t))
            .collect();
        let name = |n: &Option<Spanned<String>>| n.as_ref().map(|n| n.get_ref().clone());
        ir::StateMachine {
            name: m.name.get_ref().clone(),
            doc: m.doc.clone(),
            status: m.status.get_ref().clone(),
            command: m.command.get_ref().clone(),
            initial: name(&m.initial).unwrap_or_else(|| power_on_state(&states, &transitions)),
            fault: name(&m.fault),
            fault_code: name(&m.fault_code),
            setpoint: name(&m.setpoint),
            actual: name(&m.actual),
            communication_loss: m
                .communication_loss
                .as_ref()
                .map(|c| ir::CommunicationLoss {
                    timeout: c.get_ref().timeout.clone(),
                    fault: c.get_ref().fault,
                    span: self.span(c),
                }),

            commanded: name(&m.commanded),
            coast: name(&m.coast),
            quick_stop: name(&m.quick_stop),
            states,
            transitions,
            source: m.source.as_ref().and_then(|s| self.citation(s)),
            span: self.span(&m.name),
        }
    }

    fn machine_state(&mut self, raw: &Spanned<RawState>) -> ir::MachineState {
        let s = raw.get_ref();
        let span = self.span(raw);
        let mut status = Vec::new();
        for pattern in s.status.iter() {
            let speed = pattern
                .speed
                .as_deref()
                .and_then(|p| self.speed_phase(p, span.clone()));
            match (u16::try_from(pattern.mask), u16::try_from(pattern.value)) {
                (Ok(mask), Ok(value)) if value & !mask == 0 => status.push(ir::StatusPattern {
                    mask,
                    value,
                    when: pattern.when.as_ref().map(|w| ir::Condition {
                        parameter: w.parameter.clone(),
                        value: w.value,
                    }),
                    speed,
                }),
                _ => self.error_help(
                    VALUE_RULE,
                    span.clone(),
                    format!("state `{}`: status pattern {:#x}/{:#x} is not two 16-bit words with value bits inside the mask", s.name.get_ref(), pattern.mask, pattern.value),
                    "write `status = { mask = 0x0002, value = 0x0002 }`",
                ),
            }
        }
        let motion = match s.motion.as_ref().map(|m| (m.get_ref().as_str(), m)) {
            None | Some(("disabled", _)) => ir::Motion::Disabled,
            Some(("follow", _)) => ir::Motion::Follow,
            Some(("quick-stop", _)) => ir::Motion::QuickStop,
            Some(("ramp-stop", _)) => ir::Motion::RampStop,
            Some((other, m)) => {
                let span = self.span(m);
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("unknown motion `{other}`"),
                    "use \"disabled\", \"follow\", \"quick-stop\" or \"ramp-stop\"",
                );
                ir::Motion::Disabled
            }
        };
        ir::MachineState {
            name: s.name.get_ref().clone(),
            doc: s.doc.clone(),
            status,
            motion,
            source: s.source.as_ref().and_then(|c| self.citation(c)),
            span: self.span(&s.name),
        }
    }

    /// A status pattern's `speed` condition.
    fn speed_phase(&mut self, raw: &str, span: Span) -> Option<ir::SpeedPhase> {
        Some(match raw {
            "rising" => ir::SpeedPhase::Rising,
            "falling" => ir::SpeedPhase::Falling,
            "steady" => ir::SpeedPhase::Steady,
            "zero" => ir::SpeedPhase::Zero,
            other => {
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("unknown speed phase `{other}`"),
                    "use \"rising\", \"falling\", \"steady\" or \"zero\"",
                );
                return None;
            }
        })
    }

    fn transition(&mut self, raw: &Spanned<RawTransition>) -> Option<ir::Transition> {
        let t = raw.get_ref();
        let command = match &t.command {
            Some(c) => Some(self.int_in::<u16>(c, "command value")?),
            None => None,
        };
        let kind = match (t.kind.as_ref().map(|k| (k.get_ref().as_str(), k)), command) {
            (None | Some(("command", _)), Some(_)) => ir::TransitionKind::Command,
            (Some(("automatic", _)), None) => ir::TransitionKind::Automatic,
            (Some(("external", _)), None) => ir::TransitionKind::External,
            (kind, _) => {
                let span = kind.map_or_else(|| self.span(&t.name), |(_, k)| self.span(k));
                self.error_help(
                    VALUE_RULE,
                    span,
                    format!("transition `{}` needs a command value or a kind, not both", t.name.get_ref()),
                    "write `command = 0x0003` for a commanded transition, or `kind = \"automatic\"` / `kind = \"external\"`",
                );
                return None;
            }
        };
        Some(ir::Transition {
            name: t.name.get_ref().clone(),
            doc: t.doc.clone(),
            from: t.from.iter().cloned().collect(),
            to: t.to.clone(),
            kind,
            command,
            source: t.source.as_ref().and_then(|c| self.citation(c)),
            span: self.span(&t.name),
        })
    }
}

/// The first state no transition enters (a drive's power-on state), else the first state.
fn power_on_state(states: &[ir::MachineState], transitions: &[ir::Transition]) -> String {
    let entered = |state: &&ir::MachineState| transitions.iter().any(|t| t.to == state.name);
    states
        .iter()
        .find(|s| !entered(s))
        .or(states.first())
        .map_or_else(String::new, |s| s.name.clone())
}

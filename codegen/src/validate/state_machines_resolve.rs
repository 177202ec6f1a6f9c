//! Drive control tables refer to what exists: the safe torque off bit and a vendor machine's
//! status and command registers are 16-bit parameters, transitions name declared states, and a
//! machine fits the runtime planner.

use std::collections::BTreeSet;

use drivebus::control::machine::MAX_STATES;

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::{DataType, Device};

const RULE: &str = "state_machines_resolve";

fn word_parameter(device: &Device, name: &str, role: &str, span: &Span) -> Option<Diagnostic> {
    let message = match device.parameter(name) {
        None => format!("{role} `{name}` is not a parameter of this description"),
        Some(p) if p.data_type != DataType::Unsigned(2) => {
            format!("{role} `{name}` must be a u16 parameter")
        }
        Some(_) => return None,
    };
    Some(
        Diagnostic::error(RULE, span.clone(), message)
            .help("name a 16-bit unsigned `[[parameter]]` declared (or included) here"),
    )
}

fn cia402(device: &Device) -> Vec<Diagnostic> {
    let Some(c) = &device.cia402 else {
        return Vec::new();
    };
    let Some(sto) = &c.sto_bit else {
        return Vec::new();
    };
    let mut found: Vec<Diagnostic> =
        word_parameter(device, &sto.parameter, "`sto_bit` parameter", &c.span)
            .into_iter()
            .collect();
    if sto.bit >= 16 {
        found.push(Diagnostic::error(
            RULE,
            c.span.clone(),
            format!("`sto_bit` bit {} does not fit a 16-bit word", sto.bit),
        ));
    }
    found
}

fn vendor(device: &Device) -> Vec<Diagnostic> {
    let Some(m) = &device.state_machine else {
        return Vec::new();
    };
    let mut found = Vec::new();
    found.extend(word_parameter(
        device,
        &m.status,
        "status register",
        &m.span,
    ));
    found.extend(word_parameter(
        device,
        &m.command,
        "command register",
        &m.span,
    ));
    if m.states.is_empty() || m.states.len() > MAX_STATES {
        found.push(Diagnostic::error(
            RULE,
            m.span.clone(),
            format!(
                "a state machine has 1..={MAX_STATES} states, `{}` has {}",
                m.name,
                m.states.len()
            ),
        ));
    }
    let mut names = BTreeSet::new();
    for state in &m.states {
        if !names.insert(state.name.as_str()) {
            found.push(Diagnostic::error(
                RULE,
                state.span.clone(),
                format!("state `{}` is declared twice", state.name),
            ));
        }
    }
    let named_states = [("initial", Some(&m.initial)), ("fault", m.fault.as_ref())];
    for (role, state) in named_states {
        match state {
            Some(state) if !names.contains(state.as_str()) => found.push(
                Diagnostic::error(
                    RULE,
                    m.span.clone(),
                    format!("`{role}` names state `{state}`, which is not declared"),
                )
                .help("declare it with `[[state]]` or fix the spelling"),
            ),
            _ => {}
        }
    }
    let when = m
        .states
        .iter()
        .flat_map(|s| &s.status)
        .filter_map(|p| p.when.as_ref());
    let parameters = [
        ("fault_code", m.fault_code.as_ref()),
        ("setpoint", m.setpoint.as_ref()),
    ]
    .into_iter()
    .filter_map(|(role, name)| Some((role, name?)))
    .chain(when.map(|c| ("status pattern `when`", &c.parameter)));
    for (role, name) in parameters {
        if device.parameter(name).is_none() {
            found.push(
                Diagnostic::error(
                    RULE,
                    m.span.clone(),
                    format!("{role} `{name}` is not a parameter of this description"),
                )
                .help("name a `[[parameter]]` declared (or included) here"),
            );
        }
    }
    for t in &m.transitions {
        for state in t.from.iter().chain(std::iter::once(&t.to)) {
            if !names.contains(state.as_str()) {
                found.push(
                    Diagnostic::error(
                        RULE,
                        t.span.clone(),
                        format!(
                            "transition `{}` names state `{state}`, which is not declared",
                            t.name
                        ),
                    )
                    .help("declare it with `[[state]]` or fix the spelling"),
                );
            }
        }
    }
    found
}

/// Reports control tables that refer to missing or unsuitable parameters and states.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut found = cia402(device);
    found.extend(vendor(device));
    found
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    const STATUS: &str = r#"
[[parameter]]
name = "status"
type = "u16"
modbus = { table = "input", address = 0x0060, access = "r" }
source = { doc = "m", line = 1 }
"#;

    #[test]
    fn unknown_states_and_registers_are_reported() {
        let body = format!(
            r#"{STATUS}
[state_machine]
name = "run"
status = "status"
command = "control"
[[state]]
name = "standby"
status = {{ mask = 2, value = 2 }}
source = {{ doc = "m", line = 2 }}
[[transition]]
name = "T2"
from = "standby"
to = "running"
command = 3
source = {{ doc = "m", line = 3 }}
"#
        );
        assert_eq!(
            messages("state_machines_resolve", &body),
            [
                "command register `control` is not a parameter of this description",
                "transition `T2` names state `running`, which is not declared",
            ]
        );
    }

    #[test]
    fn named_states_and_parameters_must_exist() {
        let body = format!(
            r#"{STATUS}
[state_machine]
name = "run"
status = "status"
command = "status"
initial = "boot"
fault = "alarm"
fault_code = "error_code"
setpoint = "speed"
[[state]]
name = "standby"
status = {{ mask = 2, value = 2, when = {{ parameter = "mode", value = 1 }} }}
source = {{ doc = "m", line = 2 }}
"#
        );
        assert_eq!(
            messages("state_machines_resolve", &body),
            [
                "`initial` names state `boot`, which is not declared",
                "`fault` names state `alarm`, which is not declared",
                "fault_code `error_code` is not a parameter of this description",
                "setpoint `speed` is not a parameter of this description",
                "status pattern `when` `mode` is not a parameter of this description",
            ]
        );
    }

    #[test]
    fn sto_bit_must_name_a_word_and_fit_it() {
        let body = format!(
            "{STATUS}\n[cia402]\nsto_bit = {{ parameter = \"status\", bit = 16 }}\nsource = {{ doc = \"m\", line = 4 }}\n"
        );
        assert_eq!(
            messages("state_machines_resolve", &body),
            ["`sto_bit` bit 16 does not fit a 16-bit word"]
        );
    }
}

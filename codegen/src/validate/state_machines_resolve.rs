//! Drive control tables refer to what exists: the safe torque off bit and a vendor machine's
//! status and command registers are 16-bit parameters, transitions name declared states, a
//! machine's actual speed is an integer in its setpoint's units, and a machine fits the runtime
//! planner.

use std::collections::BTreeSet;

use drivebus_model::control::machine::MAX_STATES;

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::{DataType, Device, StateMachine};

const RULE: &str = super::rule_name(module_path!());

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
    let named_states = [
        ("initial", Some(&m.initial)),
        ("fault", m.fault.as_ref()),
        ("coast", m.coast.as_ref()),
        ("quick_stop", m.quick_stop.as_ref()),
    ];
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
        ("actual", m.actual.as_ref()),
        ("commanded", m.commanded.as_ref()),
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
    found.extend(actual_speed(device, m, m.actual.as_deref(), "actual"));
    found.extend(actual_speed(device, m, m.commanded.as_deref(), "commanded"));
    found.extend(shared_register_commands(device, m));
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

/// The machine's `actual` speed is an integer the motor's speed can be shown in, with the unit and
/// scale of the `setpoint` it follows (the simulator copies raw values). A name that is not a
/// parameter is reported with the other names.
fn actual_speed(
    device: &Device,
    m: &StateMachine,
    shown: Option<&str>,
    role: &str,
) -> Option<Diagnostic> {
    let actual = device.parameter(shown?)?;
    let message = if !actual.data_type.is_integer() {
        format!("{role} `{}` must be an integer parameter", actual.name)
    } else {
        let setpoint = device.parameter(m.setpoint.as_deref()?)?;
        if (&actual.unit, &actual.scale) == (&setpoint.unit, &setpoint.scale) {
            return None;
        }
        format!(
            "{role} `{}` and setpoint `{}` differ in unit or scale",
            actual.name, setpoint.name
        )
    };
    Some(
        Diagnostic::error(RULE, m.span.clone(), message)
            .help("name the parameter that shows the motor's speed in the setpoint's raw units"),
    )
}

/// A `command` that is a command parameter sharing its register with others (Lenze smd #1: one
/// command per bit) takes only the trigger values of those commands: each transition's value
/// must be one, since the drive does nothing else on that register.
fn shared_register_commands(device: &Device, m: &StateMachine) -> Vec<Diagnostic> {
    let Some(command) = device.parameter(&m.command) else {
        return Vec::new();
    };
    if command.command.as_ref().and_then(|c| c.value).is_none() {
        return Vec::new();
    }
    let triggers: BTreeSet<i64> = sharing_commands(device, command)
        .filter_map(|p| p.command.as_ref()?.value)
        .collect();
    m.transitions
        .iter()
        .filter_map(|t| Some((t, t.command?)))
        .filter(|(_, value)| !triggers.contains(&i64::from(*value)))
        .map(|(t, value)| {
            Diagnostic::error(
                RULE,
                t.span.clone(),
                format!(
                    "transition `{}` writes {value:#06x}, which is no command of the register of `{}`",
                    t.name, m.command
                ),
            )
            .help("write the trigger value of one of the commands sharing the register")
        })
        .collect()
}

/// The command parameters written at `command`'s Modbus registers, `command` included.
pub(crate) fn sharing_commands<'a>(
    device: &'a Device,
    command: &'a crate::ir::Parameter,
) -> impl Iterator<Item = &'a crate::ir::Parameter> {
    device.parameters.iter().filter(move |p| {
        p.command.as_ref().and_then(|c| c.value).is_some()
            && p.modbus.iter().any(|a| {
                command
                    .modbus
                    .iter()
                    .any(|b| (a.table, a.address) == (b.table, b.address))
            })
    })
}

/// Reports control tables that refer to missing or unsuitable parameters and states.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut found = cia402(device);
    found.extend(vendor(device));
    found
}

#[cfg(test)]
mod tests {
    use super::RULE;
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
            messages(RULE, &body),
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
actual = "velocity"
[[state]]
name = "standby"
status = {{ mask = 2, value = 2, when = {{ parameter = "mode", value = 1 }} }}
source = {{ doc = "m", line = 2 }}
"#
        );
        assert_eq!(
            messages(RULE, &body),
            [
                "`initial` names state `boot`, which is not declared",
                "`fault` names state `alarm`, which is not declared",
                "fault_code `error_code` is not a parameter of this description",
                "setpoint `speed` is not a parameter of this description",
                "actual `velocity` is not a parameter of this description",
                "status pattern `when` `mode` is not a parameter of this description",
            ]
        );
    }

    /// A machine with a `speed` setpoint in rpm and the given `actual`, plus `extra` parameters.
    fn machine_showing(actual: &str, extra: &str) -> String {
        format!(
            r#"{STATUS}
[[parameter]]
name = "speed"
type = "i16"
unit = "rpm"
modbus = {{ table = "holding", address = 0x0042, access = "rw" }}
source = {{ doc = "m", line = 5 }}
{extra}
[state_machine]
name = "run"
status = "status"
command = "status"
setpoint = "speed"
actual = "{actual}"
[[state]]
name = "standby"
status = {{ mask = 2, value = 2 }}
source = {{ doc = "m", line = 2 }}
"#
        )
    }

    #[test]
    fn actual_speed_is_an_integer_in_the_setpoints_units() {
        let shown = |name: &str, typ: &str, unit: &str, scale: &str| {
            let extra = format!(
                r#"
[[parameter]]
name = "{name}"
type = "{typ}"
unit = "{unit}"
{scale}
modbus = {{ table = "input", address = 0x0068, access = "r" }}
source = {{ doc = "m", line = 6 }}
"#
            );
            messages(RULE, &machine_showing(name, &extra))
        };
        assert!(shown("average", "i16", "rpm", "").is_empty());
        assert_eq!(
            shown("average", "f32", "rpm", ""),
            ["actual `average` must be an integer parameter"]
        );
        assert_eq!(
            shown("average", "i16", "Hz", ""),
            ["actual `average` and setpoint `speed` differ in unit or scale"]
        );
        assert_eq!(
            shown("filtered", "i16", "rpm", "scale = \"1/4\""),
            ["actual `filtered` and setpoint `speed` differ in unit or scale"]
        );
    }

    /// Register #1 of the Lenze smd: `stop` (4) and `start` (8) share it, one bit each.
    const COMMANDS: &str = r#"
[[parameter]]
name = "stop"
type = "u16"
command = { kind = "action", value = 4 }
modbus = { table = "holding", address = 1, access = "w" }
source = { doc = "m", line = 7 }
[[parameter]]
name = "start"
type = "u16"
command = { kind = "action", value = 8 }
modbus = { table = "holding", address = 1, access = "w" }
source = { doc = "m", line = 8 }
"#;

    fn register_machine(value: u16, coast: &str) -> String {
        format!(
            r#"{STATUS}{COMMANDS}
[state_machine]
name = "operation"
status = "status"
command = "start"
coast = "{coast}"
quick_stop = "stopping"
source = {{ doc = "m", line = 10 }}
[[state]]
name = "stopped"
status = {{ mask = 0xFF, value = 3 }}
source = {{ doc = "m", line = 2 }}
[[state]]
name = "running"
status = [ {{ mask = 0xFF, value = 7, speed = "rising" }}, {{ mask = 0xFF, value = 6 }} ]
motion = "follow"
source = {{ doc = "m", line = 3 }}
[[state]]
name = "stopping"
status = {{ mask = 0xFF, value = 8 }}
motion = "ramp-stop"
source = {{ doc = "m", line = 4 }}
[[transition]]
name = "start"
from = "stopped"
to = "running"
command = {value}
source = {{ doc = "m", line = 9 }}
"#
        )
    }

    #[test]
    fn a_register_of_commands_takes_its_commands_values_only() {
        let device = crate::validate::test_support::device(&register_machine(8, "stopped"));
        let machine = device.state_machine.unwrap();
        assert_eq!(machine.coast.as_deref(), Some("stopped"));
        assert_eq!(
            machine.states[1].status[0].speed,
            Some(crate::ir::SpeedPhase::Rising)
        );
        assert_eq!(machine.states[2].motion, crate::ir::Motion::RampStop);
        assert_eq!(
            messages(RULE, &register_machine(3, "stopped")),
            ["transition `start` writes 0x0003, which is no command of the register of `start`"]
        );
    }

    #[test]
    fn coast_and_quick_stop_name_declared_states() {
        assert_eq!(
            messages(RULE, &register_machine(8, "inhibit")),
            ["`coast` names state `inhibit`, which is not declared"]
        );
    }

    #[test]
    fn an_unknown_speed_phase_is_malformed() {
        let body = register_machine(8, "stopped").replace("\"rising\"", "\"upwards\"");
        assert_eq!(
            messages("values_are_well_formed", &body),
            ["unknown speed phase `upwards`"]
        );
    }

    #[test]
    fn commanded_speed_is_in_the_setpoints_units() {
        let extra = r#"
[[parameter]]
name = "command_hz"
type = "u16"
unit = "Hz"
modbus = { table = "input", address = 0x0069, access = "r" }
source = { doc = "m", line = 6 }
"#;
        let body = machine_showing("speed", extra)
            .replace("actual = \"speed\"", "commanded = \"command_hz\"");
        assert_eq!(
            messages(RULE, &body),
            ["commanded `command_hz` and setpoint `speed` differ in unit or scale"]
        );
    }

    #[test]
    fn sto_bit_must_name_a_word_and_fit_it() {
        let body = format!(
            "{STATUS}\n[cia402]\nsto_bit = {{ parameter = \"status\", bit = 16 }}\nsource = {{ doc = \"m\", line = 4 }}\n"
        );
        assert_eq!(
            messages(RULE, &body),
            ["`sto_bit` bit 16 does not fit a 16-bit word"]
        );
    }
}

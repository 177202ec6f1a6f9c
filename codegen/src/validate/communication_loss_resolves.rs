//! Communication loss resolves: a state machine's `communication_loss` names an integer timeout
//! parameter in `ms` or `s`, and the machine has a `fault` state for the fault it raises.

use crate::diagnostic::Diagnostic;
use crate::ir::{per_second, Device};

const RULE: &str = super::rule_name(module_path!());

/// Reports a communication loss supervision the simulator could not run.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let Some(machine) = &device.state_machine else {
        return Vec::new();
    };
    let Some(loss) = &machine.communication_loss else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut report = |message: String| {
        out.push(Diagnostic::error(RULE, loss.span.clone(), message));
    };
    match device.parameter(&loss.timeout) {
        None => report(format!(
            "the communication loss timeout `{}` is not a parameter",
            loss.timeout
        )),
        Some(p) if !p.data_type.is_integer() => report(format!(
            "the communication loss timeout `{}` is not an integer",
            loss.timeout
        )),
        Some(p) if p.unit.as_deref().and_then(per_second).is_none() => report(format!(
            "the communication loss timeout `{}` is not in `ms` or `s`",
            loss.timeout
        )),
        Some(_) => {}
    }
    if machine.fault.is_none() {
        report(format!(
            "a communication loss raises fault {:#06x}, but `{}` has no `fault` state",
            loss.fault, machine.name
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    fn body(loss: &str, fault_state: bool) -> String {
        let fault = if fault_state {
            "fault = \"alarm\"\n"
        } else {
            ""
        };
        format!(
            r#"
[state_machine]
name = "run"
status = "status"
command = "command"
{fault}communication_loss = {loss}
source = {{ doc = "m", line = 1 }}

[[state]]
name = "standby"
status = {{ mask = 1, value = 1 }}

[[state]]
name = "alarm"
status = {{ mask = 2, value = 2 }}

[[parameter]]
name = "status"
type = "u16"
modbus = {{ table = "input", address = 1, access = "r" }}
source = {{ doc = "m", line = 2 }}

[[parameter]]
name = "command"
type = "u16"
modbus = {{ table = "holding", address = 1, access = "rw" }}
source = {{ doc = "m", line = 3 }}

[[parameter]]
name = "loss_time"
type = "u16"
unit = "ms"
modbus = {{ table = "holding", address = 2, access = "rw" }}
source = {{ doc = "m", line = 4 }}
"#
        )
    }

    #[test]
    fn a_timeout_in_ms_with_a_fault_state_resolves() {
        let text = body(r#"{ timeout = "loss_time", fault = 0x7521 }"#, true);
        assert!(messages(RULE, &text).is_empty());
    }

    #[test]
    fn the_timeout_must_be_a_time_and_the_fault_a_state() {
        assert_eq!(
            messages(
                RULE,
                &body(r#"{ timeout = "status", fault = 1 }"#, true)
            ),
            ["the communication loss timeout `status` is not in `ms` or `s`"]
        );
        assert_eq!(
            messages(
                RULE,
                &body(r#"{ timeout = "missing", fault = 1 }"#, false)
            ),
            [
                "the communication loss timeout `missing` is not a parameter",
                "a communication loss raises fault 0x0001, but `run` has no `fault` state",
            ]
        );
    }
}

//! Every parameter, PDO mapping, SRDO, enum, flags type, record, control table, lock, unlock,
//! watchdog, ramp and `combined_commands` rule cites the manual line it comes from.

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::{Citation, Device};

const RULE: &str = super::rule_name(module_path!());

fn uncited(kind: &str, name: &str, span: &Span, source: &Option<Citation>) -> Option<Diagnostic> {
    let message = match source {
        None => format!("{kind} `{name}` cites no source"),
        // A standard is cited by its section; a manual by its line.
        Some(c) if c.cited.standard && c.section.is_some() => return None,
        Some(c) if c.line.is_none() => format!("{kind} `{name}` cites no line of `{}`", c.doc()),
        Some(_) => return None,
    };
    Some(
        Diagnostic::error(RULE, span.clone(), message)
            .help("add `source = { doc = \"<id>\", section = \"...\", line = N }`"),
    )
}

/// Reports items without a citation or without a line number.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let parameters = device
        .parameters
        .iter()
        .map(|p| ("parameter", &p.name, &p.spans.name, &p.source));
    let enums = device
        .enums
        .iter()
        .map(|e| ("enum", &e.name, &e.span, &e.source));
    let flags = device
        .flags
        .iter()
        .map(|f| ("flags", &f.name, &f.span, &f.source));
    let records = device
        .records
        .iter()
        .map(|r| ("record", &r.name, &r.span, &r.source));
    let machine = device.state_machine.iter().flat_map(|m| {
        let states = m
            .states
            .iter()
            .map(|s| ("state", &s.name, &s.span, &s.source));
        let transitions = m
            .transitions
            .iter()
            .map(|t| ("transition", &t.name, &t.span, &t.source));
        std::iter::once(("state machine", &m.name, &m.span, &m.source))
            .chain(states)
            .chain(transitions)
    });
    let cia402_name = String::from("cia402");
    let cia402 = device
        .cia402
        .iter()
        .map(|c| ("table", &cia402_name, &c.span, &c.source));
    let mappings = device
        .mappings
        .iter()
        .map(|m| (m.label(), &m.name, &m.span, &m.source));
    let watchdog_name = String::from("watchdog");
    let lock = device.lock.iter().flat_map(|l| {
        let unlocks = l
            .unlocks
            .iter()
            .map(|u| ("unlock", &u.name, &u.span, &u.source));
        let watchdog = l
            .watchdog
            .iter()
            .map(|w| ("table", &watchdog_name, &w.span, &w.source));
        std::iter::once(("lock command", &l.command, &l.span, &l.source))
            .chain(unlocks)
            .chain(watchdog)
    });
    let ramps = device
        .ramps
        .iter()
        .map(|r| ("ramp of", &r.setpoint, &r.span, &r.source));
    let combined_name = String::from("combined_commands");
    let combined = device
        .modbus
        .iter()
        .flat_map(|m| &m.combined_commands)
        .map(|c| ("table", &combined_name, &c.span, &c.source));
    parameters
        .chain(lock)
        .chain(ramps)
        .chain(combined)
        .chain(mappings)
        .chain(enums)
        .chain(flags)
        .chain(records)
        .chain(machine)
        .chain(cia402)
        .filter_map(|(kind, name, span, source)| uncited(kind, name, span, source))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn missing_source_and_missing_line_are_reported() {
        let body = r#"
[[parameter]]
name = "a"
type = "u8"
modbus = { table = "holding", address = 1 }
[[parameter]]
name = "b"
type = "u8"
modbus = { table = "holding", address = 2 }
source = { doc = "m", section = "2" }
"#;
        assert_eq!(
            messages(RULE, body),
            [
                "parameter `a` cites no source",
                "parameter `b` cites no line of `m`"
            ]
        );
    }

    #[test]
    fn a_standard_is_cited_by_section_but_not_without_one() {
        let body = r#"
[[source]]
id = "cia402"
file = "CiA 402-2"
title = "CiA 402-2"
standard = true
[[parameter]]
name = "a"
type = "u8"
modbus = { table = "holding", address = 1 }
source = { doc = "cia402", section = "6082h End velocity" }
[[parameter]]
name = "b"
type = "u8"
modbus = { table = "holding", address = 2 }
source = { doc = "cia402" }
"#;
        assert_eq!(messages(RULE, body), ["parameter `b` cites no line of `cia402`"]);
    }
}

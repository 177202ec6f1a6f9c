//! The order a push writes in: modes first, then every parameter after those that bound it or
//! scale it, otherwise the description's order.

use drivegen::ir::{Device, Parameter};

use super::selection;

/// One parameter whose value on the drive differs from the file's.
pub struct Change<'d> {
    /// The parameter.
    pub parameter: &'d Parameter,
    /// What the drive holds now (empty for a step of a sequence, such as a PDO mapping's).
    pub current: Vec<u8>,
    /// What the file holds.
    pub wanted: Vec<u8>,
    /// The file line.
    pub line: u32,
    /// Why the file's value is not one the description allows, if it is not (refused before
    /// anything is written).
    pub invalid: Option<String>,
}

/// `changes` in an order that works: each after the modes and after the parameters its value
/// is checked against ([`selection::depends_on`]); a cycle falls back to the description's order.
pub fn order<'d>(device: &Device, mut changes: Vec<Change<'d>>) -> Vec<Change<'d>> {
    let position = |p: &Parameter| device.parameters.iter().position(|q| q.name == p.name);
    changes.sort_by_key(|c| position(c.parameter));
    let names: Vec<&str> = changes.iter().map(|c| c.parameter.name.as_str()).collect();
    let modes: Vec<&str> = changes
        .iter()
        .filter(|c| selection::is_mode(device, c.parameter))
        .map(|c| c.parameter.name.as_str())
        .collect();
    let before: Vec<Vec<String>> = changes
        .iter()
        .map(|c| {
            let mut after: Vec<&str> = selection::depends_on(c.parameter);
            if !modes.contains(&c.parameter.name.as_str()) {
                after.extend(&modes);
            }
            after.retain(|n| names.contains(n) && *n != c.parameter.name);
            after.into_iter().map(str::to_owned).collect()
        })
        .collect();
    let mut pending: Vec<(Change<'d>, Vec<String>)> = changes.into_iter().zip(before).collect();
    let mut ordered: Vec<Change<'d>> = Vec::new();
    while !pending.is_empty() {
        let ready = pending
            .iter()
            .position(|(_, after)| {
                after
                    .iter()
                    .all(|n| ordered.iter().any(|o| &o.parameter.name == n))
            })
            .unwrap_or(0);
        ordered.push(pending.remove(ready).0);
    }
    ordered
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::config::selection::tests::shipped;

    fn change<'d>(device: &'d Device, name: &str) -> Change<'d> {
        Change {
            parameter: device.parameter(name).unwrap(),
            current: Vec::new(),
            wanted: Vec::new(),
            line: 0,
            invalid: None,
        }
    }

    fn ordered(device: &Device, names: &[&str]) -> Vec<String> {
        let changes = names.iter().map(|n| change(device, n)).collect();
        order(device, changes)
            .iter()
            .map(|c| c.parameter.name.clone())
            .collect()
    }

    #[test]
    fn modes_first_then_bounds_before_what_they_bound() {
        let lenze = shipped("lenze-smd");
        // pi_setpoint lies within pi_min_feedback ... pi_max_feedback (declared after it).
        assert_eq!(
            ordered(
                &lenze,
                &[
                    "pi_setpoint",
                    "acceleration_time",
                    "pi_max_feedback",
                    "control_source"
                ]
            ),
            [
                "control_source",
                "acceleration_time",
                "pi_max_feedback",
                "pi_setpoint"
            ]
        );
    }
}

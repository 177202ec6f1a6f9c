//! The unlocks a push needs and the lock after it, as the description's `[lock]` and
//! `[[unlock]]` declare them: the scopes of the parameters to write, the unlock that opens them
//! (its requirement holding), the key it is granted with, and the lock command.

use drivebus::interpret;
use drivegen::ir::{Device, GrantKey, Parameter, Unlock};

use crate::connect::Session;
use crate::error::CliError;

/// One write of the push that is not a value of the file: a grant or the lock command.
pub struct Step<'d> {
    /// Why: `unlock <name>` or `lock`.
    pub what: String,
    /// The parameter written.
    pub parameter: &'d Parameter,
    /// The raw bytes written.
    pub bytes: Vec<u8>,
    /// The bytes are a password, not to be printed.
    pub secret: bool,
}

/// The grants that open every scope `parameters` need, in the order to write them.
pub fn unlocks<'d>(
    device: &'d Device,
    session: &mut Session,
    parameters: &[&Parameter],
    password: Option<&str>,
) -> Result<Vec<Step<'d>>, CliError> {
    let Some(lock) = &device.lock else {
        return Ok(Vec::new());
    };
    let mut needed: Vec<&str> = parameters
        .iter()
        .filter_map(|p| lock.scope_of(p))
        .map(|s| s.name.as_str())
        .collect();
    needed.sort_unstable();
    needed.dedup();
    let mut steps = Vec::new();
    while !needed.is_empty() {
        let usable: Vec<&Unlock> = lock
            .unlocks
            .iter()
            .filter(|u| u.allows.iter().any(|a| needed.contains(&a.as_str())))
            .filter(|u| requirement_holds(device, session, u, &needed))
            .collect();
        // The unlock that opens the most of what is needed and the least beyond it.
        let best = usable
            .iter()
            .max_by_key(|u| {
                let opens = u.allows.iter().filter(|a| needed.contains(&a.as_str())).count();
                (opens, std::cmp::Reverse(u.allows.len() - opens))
            })
            .ok_or_else(|| {
                CliError::NoAccess(format!(
                    "no unlock of the description opens {} now (an unlock's requirement does not hold)",
                    needed.join(", ")
                ))
            })?;
        needed.retain(|n| !best.allows.iter().any(|a| a == n));
        steps.push(grant(device, session, best, password)?);
    }
    Ok(steps)
}

/// The lock command, written after a push that unlocked.
pub fn relock(device: &Device) -> Option<Step<'_>> {
    let lock = device.lock.as_ref()?;
    let parameter = device.parameter(&lock.command)?;
    let value = parameter
        .command
        .as_ref()
        .and_then(|c| c.value)
        .unwrap_or(1);
    Some(Step {
        what: "lock".into(),
        parameter,
        bytes: interpret::raw::from_int(parameter.data_type, value.into()),
        secret: false,
    })
}

/// Whether the drive holds a value the unlock requires, where it requires one for a scope that
/// is needed.
fn requirement_holds(
    device: &Device,
    session: &mut Session,
    unlock: &Unlock,
    needed: &[&str],
) -> bool {
    let Some(requirement) = &unlock.requires else {
        return true;
    };
    if !requirement
        .scopes
        .iter()
        .any(|s| needed.contains(&s.as_str()))
    {
        return true;
    }
    let Some(parameter) = device.parameter(&requirement.parameter) else {
        return false;
    };
    let value = super::live::read_one(session, parameter)
        .ok()
        .and_then(|bytes| interpret::raw::to_int(parameter.data_type, &bytes));
    value.is_some_and(|v| requirement.values.iter().any(|r| i128::from(*r) == v))
}

/// The write that grants `unlock`: its fixed value, or the password (`--password`, else the
/// password parameter read from the drive).
fn grant<'d>(
    device: &'d Device,
    session: &mut Session,
    unlock: &Unlock,
    password: Option<&str>,
) -> Result<Step<'d>, CliError> {
    let parameter = crate::commands::parameter(device, &unlock.grant.parameter)?;
    let bytes = match (&unlock.grant.key, password) {
        (GrantKey::Value(value), _) => {
            interpret::raw::from_int(parameter.data_type, i128::from(*value))
        }
        (GrantKey::Password(_), Some(text)) => interpret::parse(device, parameter, text)
            .map_err(|cause| CliError::Usage(format!("--password: {cause}")))?,
        (GrantKey::Password(name), None) => {
            let source = crate::commands::parameter(device, name)?;
            let read = super::live::read_one(session, source).map_err(|e| {
                CliError::Usage(format!(
                    "unlock {} needs the password {name}, which could not be read ({e}): give --password",
                    unlock.name
                ))
            })?;
            let raw = interpret::raw::to_int(source.data_type, &read).unwrap_or_default();
            interpret::raw::from_int(parameter.data_type, raw)
        }
    };
    Ok(Step {
        what: format!("unlock {}", unlock.name),
        parameter,
        bytes,
        secret: matches!(unlock.grant.key, GrantKey::Password(_)),
    })
}

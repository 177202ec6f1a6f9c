//! Changes to the write lock (`[lock]`, `[[unlock]]`): a parameter whose scope changes moves its
//! setter between the handle and the unlock guards (breaking); an unlock that disappears takes its
//! `unlock_<name>` method with it; a changed grant, requirement or set of ends writes or checks
//! differently.

use super::{match_by_name, Change, Impact};
use crate::ir::{Device, Unlock};

/// Compares the locks of two descriptions.
pub(super) fn compare(old: &Device, new: &Device, out: &mut Vec<Change>) {
    scopes(old, new, out);
    let unlocks = |d: &'_ Device| -> Vec<Unlock> {
        d.lock
            .as_ref()
            .map(|l| l.unlocks.clone())
            .unwrap_or_default()
    };
    let (before, after) = (unlocks(old), unlocks(new));
    let matched = match_by_name(&before, &after, |u| &u.name);
    for u in matched.removed {
        out.push(Change::new(Impact::Breaking, subject(u), "removed"));
    }
    for u in matched.added {
        out.push(Change::new(Impact::Compatible, subject(u), "added"));
    }
    for (o, n) in matched.both {
        unlock(o, n, out);
    }
}

fn subject(u: &Unlock) -> String {
    format!("unlock `{}`", u.name)
}

/// The scope each parameter present in both needs.
fn scopes(old: &Device, new: &Device, out: &mut Vec<Change>) {
    for o in &old.parameters {
        let Some(n) = new.parameter(&o.name) else {
            continue; // reported as removed by `parameters`
        };
        let before = old.lock_scope_of(o).map(|s| s.name.as_str());
        let after = new.lock_scope_of(n).map(|s| s.name.as_str());
        let what = match (before, after) {
            (None, Some(s)) => format!("now needs an unlock (scope `{s}`): its setter moves from the handle to the unlock guard"),
            (Some(s), None) => format!("no longer needs an unlock (scope `{s}`): its setter moves from the guard to the handle"),
            (Some(a), Some(b)) if a != b => format!("unlock scope `{a}` → `{b}`"),
            _ => continue,
        };
        out.push(Change::new(
            Impact::Breaking,
            format!("parameter `{}`", o.name),
            what,
        ));
    }
}

fn unlock(o: &Unlock, n: &Unlock, out: &mut Vec<Change>) {
    if o.allows != n.allows {
        out.push(Change::new(
            Impact::Breaking,
            subject(o),
            format!("opens {:?} → {:?}", o.allows, n.allows),
        ));
    }
    if o.grant.parameter != n.grant.parameter || o.grant.key != n.grant.key {
        out.push(Change::new(
            Impact::Behaviour,
            subject(o),
            format!(
                "grant `{}` {:?} → `{}` {:?}",
                o.grant.parameter, o.grant.key, n.grant.parameter, n.grant.key
            ),
        ));
    }
    let requirement = |u: &Unlock| {
        u.requires
            .as_ref()
            .map(|r| (r.parameter.clone(), r.values.clone()))
    };
    if requirement(o) != requirement(n) {
        out.push(Change::new(
            Impact::Behaviour,
            subject(o),
            format!("requirement {:?} → {:?}", requirement(o), requirement(n)),
        ));
    }
    if o.ends != n.ends {
        out.push(Change::new(
            Impact::Behaviour,
            subject(o),
            format!("ends {:?} → {:?}", o.ends, n.ends),
        ));
    }
}

#[cfg(test)]
mod tests {
    use crate::diff::{diff, Impact};
    use crate::validate::test_support::device;

    const PARAMETERS: &str = r#"
[[parameter]]
name = "lock_command"
type = "u16"
command = { kind = "action", value = 2 }
modbus = { table = "holding", address = 1, access = "w" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "grant"
type = "u16"
modbus = { table = "holding", address = 48, access = "w" }
source = { doc = "m", line = 2 }

[[parameter]]
name = "speed"
type = "u16"
modbus = { table = "holding", address = 40, access = "rw" }
source = { doc = "m", line = 3 }
"#;

    fn lock(scope: &str, grant: i64) -> String {
        format!(
            r#"
[lock]
command = "lock_command"
refusal = 0x01
scopes = [ {scope} ]
source = {{ doc = "m", line = 4 }}

[[unlock]]
name = "controls"
grant = {{ parameter = "grant", value = {grant} }}
allows = ["controls"]
source = {{ doc = "m", line = 5 }}
{PARAMETERS}"#
        )
    }

    fn changes(old: &str, new: &str) -> Vec<(Impact, String)> {
        diff(&device(old), &device(new))
            .into_iter()
            .map(|c| (c.impact, format!("{}: {}", c.subject, c.what)))
            .collect()
    }

    #[test]
    fn a_parameter_that_starts_needing_an_unlock_breaks() {
        let gated = lock(r#"{ name = "controls", parameters = ["speed"] }"#, 0);
        let free = PARAMETERS.to_string();
        assert_eq!(
            changes(&free, &gated),
            [
                (Impact::Breaking, "parameter `speed`: now needs an unlock (scope `controls`): its setter moves from the handle to the unlock guard".into()),
                (Impact::Compatible, "unlock `controls`: added".into()),
            ]
        );
        assert_eq!(
            changes(&gated, &free)[0],
            (Impact::Breaking, "parameter `speed`: no longer needs an unlock (scope `controls`): its setter moves from the guard to the handle".into())
        );
    }

    #[test]
    fn a_changed_grant_is_behaviour() {
        let scope = r#"{ name = "controls", parameters = ["speed"] }"#;
        assert_eq!(
            changes(&lock(scope, 0), &lock(scope, 1)),
            [(
                Impact::Behaviour,
                "unlock `controls`: grant `grant` Value(0) → `grant` Value(1)".into()
            )]
        );
    }
}

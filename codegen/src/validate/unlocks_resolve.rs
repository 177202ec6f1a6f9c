//! The write lock resolves: its command, scopes, grants, passwords, requirements and watchdog
//! name parameters that can do their part, every scope is opened by some unlock, and the
//! generated `unlock_<name>` methods collide with no accessor.

use std::collections::BTreeSet;

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::{CommandKind, Device, GrantKey, Lock, Parameter, Unlock, UnlockEnd, Watchdog};
use crate::names;

const RULE: &str = super::rule_name(module_path!());

/// Reports lock data that names nothing usable.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let Some(lock) = &device.lock else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut report = |span: &Span, message: String| {
        out.push(Diagnostic::error(RULE, span.clone(), message));
    };
    command(device, lock, &mut report);
    scopes(device, lock, &mut report);
    if lock.unlocks.len() > drivebus_model::write_lock::MAX_UNLOCKS {
        report(
            &lock.span,
            format!(
                "{} unlocks: a lock has at most {} (the drive handle follows them in one word)",
                lock.unlocks.len(),
                drivebus_model::write_lock::MAX_UNLOCKS
            ),
        );
    }
    let mut seen = BTreeSet::new();
    for unlock in &lock.unlocks {
        if !seen.insert(unlock.name.as_str()) {
            report(
                &unlock.span,
                format!("unlock `{}` is declared twice", unlock.name),
            );
        }
        self::unlock(device, lock, unlock, &mut report);
    }
    if let Some(watchdog) = &lock.watchdog {
        self::watchdog(device, lock, watchdog, &mut report);
    }
    generated_names(device, lock, &mut report);
    out
}

/// Methods of the generated guard besides the setters.
const GUARD_METHODS: [&str; 4] = ["drive", "lock", "new", "write_lock"];

/// The generated `unlock` module's names (a marker per unlock, an `Opens<Scope>` trait per
/// scope) are distinct, and no setter on the guard takes a name of the guard's own methods.
fn generated_names(device: &Device, lock: &Lock, report: &mut impl FnMut(&Span, String)) {
    let mut taken: BTreeSet<String> = BTreeSet::new();
    let markers = lock
        .unlocks
        .iter()
        .map(|u| (names::camel(&u.name), &u.span));
    let traits = lock
        .scopes
        .iter()
        .map(|s| (format!("Opens{}", names::camel(&s.name)), &s.span));
    for (name, span) in markers.chain(traits) {
        if !taken.insert(name.clone()) {
            report(
                span,
                format!("the generated name `unlock::{name}` is taken twice"),
            );
        }
    }
    for p in &device.parameters {
        let method = names::method(&p.name);
        if device.lock_scope_of(p).is_some() && GUARD_METHODS.contains(&method.as_str()) {
            report(
                &lock.span,
                format!(
                    "the setter `{method}` of `{}` would shadow the unlock guard's own method",
                    p.name
                ),
            );
        }
    }
}

/// Why `p` cannot be read as an integer, if it cannot.
fn unreadable_integer(p: &Parameter) -> Option<&'static str> {
    let readable = p.modbus.iter().any(|a| a.access.read)
        || p.canopen.iter().any(|a| a.access.read)
        || p.rs232.iter().any(|a| a.access.read);
    if !p.data_type.is_integer() {
        Some("it is not an integer")
    } else if !readable {
        Some("it is not readable")
    } else {
        None
    }
}

/// The parameter called `name`, or a report that there is none.
fn resolve<'d>(
    device: &'d Device,
    name: &str,
    role: &str,
    span: &Span,
    report: &mut impl FnMut(&Span, String),
) -> Option<&'d Parameter> {
    let found = device.parameter(name);
    if found.is_none() {
        report(span, format!("{role} `{name}` is not a parameter"));
    }
    found
}

fn command(device: &Device, lock: &Lock, report: &mut impl FnMut(&Span, String)) {
    let Some(p) = resolve(
        device,
        &lock.command,
        "the lock command",
        &lock.span,
        report,
    ) else {
        return;
    };
    let is_action = p
        .command
        .as_ref()
        .is_some_and(|c| c.kind == CommandKind::Action && c.value.is_some());
    if !is_action || !p.is_writable() {
        report(
            &lock.span,
            format!(
                "the lock command `{}` is not a writable action command with a value",
                p.name
            ),
        );
    }
}

fn scopes(device: &Device, lock: &Lock, report: &mut impl FnMut(&Span, String)) {
    let mut names = BTreeSet::new();
    let mut members = BTreeSet::new();
    let mut rest = 0;
    for scope in &lock.scopes {
        if !names.insert(scope.name.as_str()) {
            report(
                &scope.span,
                format!("scope `{}` is declared twice", scope.name),
            );
        }
        rest += usize::from(scope.rest);
        if scope.rest && rest > 1 {
            report(
                &scope.span,
                "only one scope can hold the `rest`".to_string(),
            );
        }
        if scope.parameters.is_empty() && !scope.rest {
            report(
                &scope.span,
                format!(
                    "scope `{}` has no parameters and is not the `rest`",
                    scope.name
                ),
            );
        }
        for name in &scope.parameters {
            let role = format!("scope `{}` lists", scope.name);
            let Some(p) = resolve(device, name, &role, &scope.span, report) else {
                continue;
            };
            if !members.insert(name.as_str()) {
                report(&scope.span, format!("`{name}` is in more than one scope"));
            } else if lock.is_exempt(name) {
                report(
                    &scope.span,
                    format!(
                        "`{name}` is the lock command or a grant: it is written without an unlock"
                    ),
                );
            } else if !p.is_writable() {
                report(
                    &scope.span,
                    format!("`{name}` in scope `{}` is not writable", scope.name),
                );
            }
        }
        if lock.unlocks_opening(&scope.name).next().is_none() {
            report(
                &scope.span,
                format!("no unlock allows scope `{}`", scope.name),
            );
        }
    }
}

fn unlock(device: &Device, lock: &Lock, unlock: &Unlock, report: &mut impl FnMut(&Span, String)) {
    let method = format!("unlock_{}", names::snake(&unlock.name));
    if device
        .parameters
        .iter()
        .any(|p| names::method(&p.name) == method)
    {
        report(
            &unlock.span,
            format!("`{method}` would collide with the accessor of parameter `{method}`"),
        );
    }
    if unlock.allows.is_empty() {
        report(
            &unlock.span,
            format!("unlock `{}` allows no scope", unlock.name),
        );
    }
    for scope in &unlock.allows {
        if !lock.scopes.iter().any(|s| &s.name == scope) {
            report(
                &unlock.span,
                format!(
                    "unlock `{}` allows `{scope}`, which is not a scope",
                    unlock.name
                ),
            );
        }
    }
    let grant = &unlock.grant;
    if let Some(p) = resolve(device, &grant.parameter, "the grant", &grant.span, report) {
        if !p.is_writable() || !p.data_type.is_integer() {
            report(
                &grant.span,
                format!("the grant `{}` is not a writable integer", p.name),
            );
        }
        if let GrantKey::Value(value) = grant.key {
            if !fits(p, value) {
                report(&grant.span, format!("{value} does not fit `{}`", p.name));
            }
        }
    }
    if let GrantKey::Password(password) = &grant.key {
        if let Some(p) = resolve(device, password, "the password", &grant.span, report) {
            if !p.data_type.is_integer() {
                report(
                    &grant.span,
                    format!("the password `{}` is not an integer", p.name),
                );
            }
        }
    }
    match &unlock.requires {
        Some(r) => {
            if let Some(p) = resolve(device, &r.parameter, "the requirement", &r.span, report) {
                if let Some(why) = unreadable_integer(p) {
                    report(
                        &r.span,
                        format!("the requirement `{}` cannot be checked: {why}", p.name),
                    );
                }
                for value in r.values.iter().filter(|v| !fits(p, **v)) {
                    report(&r.span, format!("{value} does not fit `{}`", p.name));
                }
            }
            for scope in r.scopes.iter().filter(|s| !unlock.allows.contains(s)) {
                report(
                    &r.span,
                    format!(
                        "the requirement of `{}` guards scope `{scope}`, which the unlock does \
                         not allow",
                        unlock.name
                    ),
                );
            }
        }
        None if unlock.ends.contains(&UnlockEnd::RequirementLost) => report(
            &unlock.span,
            format!(
                "unlock `{}` ends on `requirement_lost` but has no `requires`",
                unlock.name
            ),
        ),
        None => {}
    }
    if unlock.ends.contains(&UnlockEnd::SerialTimeout) && lock.watchdog.is_none() {
        report(
            &unlock.span,
            format!(
                "unlock `{}` ends on `serial_timeout` but there is no `[watchdog]`",
                unlock.name
            ),
        );
    }
}

fn watchdog(device: &Device, lock: &Lock, w: &Watchdog, report: &mut impl FnMut(&Span, String)) {
    for (name, role) in [
        (&w.timeout, "the watchdog timeout"),
        (&w.action, "the watchdog action"),
    ] {
        if let Some(p) = resolve(device, name, role, &w.span, report) {
            if let Some(why) = unreadable_integer(p) {
                report(
                    &w.span,
                    format!("{role} `{}` cannot be read: {why}", p.name),
                );
            }
        }
    }
    let mut values = BTreeSet::new();
    for a in &w.actions {
        if !values.insert(a.value) {
            report(
                &a.span,
                format!("the watchdog action {} is described twice", a.value),
            );
        }
    }
    if let Some(action) = device.parameter(&w.action) {
        let documented = action
            .enumeration
            .as_ref()
            .and_then(|e| device.enums.iter().find(|x| &x.name == e));
        for value in documented.into_iter().flat_map(|e| &e.values) {
            if !values.contains(&value.value) {
                report(
                    &w.span,
                    format!(
                        "`{}` value {} ({}) has no watchdog action",
                        action.name, value.value, value.name
                    ),
                );
            }
        }
    }
    for scope in &w.acts_with {
        if !lock.scopes.iter().any(|s| &s.name == scope) {
            report(
                &w.span,
                format!("the watchdog acts with `{scope}`, which is not a scope"),
            );
        }
    }
}

/// Whether `value` fits the integer type of `p`.
fn fits(p: &Parameter, value: i64) -> bool {
    p.data_type
        .integer_bounds()
        .is_none_or(|(lo, hi)| (lo..=hi).contains(&i128::from(value)))
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::{device, messages};

    /// A drive with a lock command, two grants, a password, a requirement and a watchdog.
    const PARAMETERS: &str = r#"
[[enum]]
name = "timeout_action"
type = "u16"
values = [ { name = "off", value = 0 }, { name = "stop", value = 1 } ]
source = { doc = "m", line = 7 }

[[parameter]]
name = "lock_command"
type = "u16"
command = { kind = "action", value = 2 }
modbus = { table = "holding", address = 1, access = "w" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "start"
type = "u16"
command = { kind = "action", value = 8 }
modbus = { table = "holding", address = 1, access = "w" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "unlock_word"
type = "u16"
modbus = { table = "holding", address = 48, access = "w" }
source = { doc = "m", line = 2 }

[[parameter]]
name = "password"
type = "u16"
modbus = { table = "holding", address = 94, access = "rw" }
source = { doc = "m", line = 3 }

[[parameter]]
name = "control_source"
type = "u16"
modbus = { table = "holding", address = 51, access = "rw" }
source = { doc = "m", line = 4 }

[[parameter]]
name = "timeout"
type = "u16"
unit = "ms"
modbus = { table = "holding", address = 133, access = "rw" }
source = { doc = "m", line = 5 }

[[parameter]]
name = "action"
type = "u16"
enum = "timeout_action"
modbus = { table = "holding", address = 132, access = "rw" }
source = { doc = "m", line = 6 }
"#;

    const LOCK: &str = r#"
[lock]
command = "lock_command"
refusal = 0x01
source = { doc = "m", line = 8 }
scopes = [ { name = "controls", parameters = ["start"] }, { name = "parameters", rest = true } ]

[[unlock]]
name = "controls"
grant = { parameter = "unlock_word", value = 0 }
allows = ["controls"]
requires = { parameter = "control_source", values = [10, 11] }
ends = ["lock", "requirement_lost", "power_down", "serial_timeout"]
source = { doc = "m", line = 9 }

[[unlock]]
name = "all"
grant = { parameter = "unlock_word", password = "password" }
allows = ["controls", "parameters"]
ends = ["lock", "serial_timeout"]
source = { doc = "m", line = 10 }

[watchdog]
timeout = "timeout"
action = "action"
actions = [ { value = 0, does = "disabled" }, { value = 1, does = "quick_stop" } ]
acts_with = ["controls"]
source = { doc = "m", line = 11 }
"#;

    fn body(lock: &str) -> String {
        format!("{lock}\n{PARAMETERS}")
    }

    #[test]
    fn a_complete_lock_resolves_and_gates_the_right_parameters() {
        let device = device(&body(LOCK));
        let lock = device.lock.as_ref().unwrap();
        let scope = |name: &str| {
            device
                .lock_scope_of(device.parameter(name).unwrap())
                .map(|s| s.name.as_str())
        };
        assert_eq!(scope("start"), Some("controls"));
        assert_eq!(scope("control_source"), Some("parameters"));
        assert_eq!(scope("lock_command"), None, "the lock command is exempt");
        assert_eq!(scope("unlock_word"), None, "a grant is exempt");
        assert_eq!(lock.unlocks_opening("parameters").count(), 1);
        assert!(messages(RULE, &body(LOCK)).is_empty());
    }

    #[test]
    fn a_requirement_guards_only_scopes_its_unlock_allows() {
        let guarded = LOCK.replace(
            r#"values = [10, 11] }"#,
            r#"values = [10, 11], scopes = ["parameters"] }"#,
        );
        assert_eq!(
            messages(RULE, &body(&guarded)),
            ["the requirement of `controls` guards scope `parameters`, which the unlock does not allow"]
        );
        let device = device(&body(LOCK));
        let controls = &device.lock.as_ref().unwrap().unlocks[0];
        assert_eq!(
            controls.requires.as_ref().unwrap().scopes,
            ["controls"],
            "by default the scopes the unlock allows"
        );
    }

    #[test]
    fn unknown_names_are_reported() {
        let lock = LOCK
            .replace(r#"command = "lock_command""#, r#"command = "lock_it""#)
            .replace(r#"password = "password""#, r#"password = "secret""#)
            .replace(r#"allows = ["controls"]"#, r#"allows = ["drive"]"#);
        assert_eq!(
            messages(RULE, &body(&lock)),
            [
                "the lock command `lock_it` is not a parameter",
                "unlock `controls` allows `drive`, which is not a scope",
                "the password `secret` is not a parameter",
            ]
        );
    }

    #[test]
    fn a_scope_nobody_opens_and_a_grant_in_a_scope_are_reported() {
        let lock = LOCK
            .replace(
                r#"allows = ["controls", "parameters"]"#,
                r#"allows = ["controls"]"#,
            )
            .replace(
                r#"parameters = ["start"]"#,
                r#"parameters = ["start", "unlock_word"]"#,
            );
        assert_eq!(
            messages(RULE, &body(&lock)),
            [
                "`unlock_word` is the lock command or a grant: it is written without an unlock",
                "no unlock allows scope `parameters`",
            ]
        );
    }

    #[test]
    fn requirements_and_watchdog_actions_must_fit() {
        let lock = LOCK
            .replace("values = [10, 11]", "values = [10, 70000]")
            .replace(r#", { value = 1, does = "quick_stop" }"#, "");
        assert_eq!(
            messages(RULE, &body(&lock)),
            [
                "70000 does not fit `control_source`",
                "`action` value 1 (stop) has no watchdog action",
            ]
        );
    }

    #[test]
    fn ends_need_what_they_observe() {
        let lock = LOCK.replace(
            "requires = { parameter = \"control_source\", values = [10, 11] }\n",
            "",
        );
        assert_eq!(
            messages(RULE, &body(&lock)),
            ["unlock `controls` ends on `requirement_lost` but has no `requires`"]
        );
    }

    #[test]
    fn generated_names_do_not_collide() {
        let lock = LOCK.replace(r#"name = "all""#, r#"name = "opens_controls""#);
        assert_eq!(
            messages(RULE, &body(&lock)),
            ["the generated name `unlock::OpensControls` is taken twice"]
        );
        let parameters = PARAMETERS.replace(r#"name = "control_source""#, r#"name = "drive""#);
        let lock = LOCK.replace(r#"parameter = "control_source""#, r#"parameter = "drive""#);
        assert_eq!(
            messages(RULE, &format!("{lock}\n{parameters}")),
            ["the setter `drive` of `drive` would shadow the unlock guard's own method"]
        );
    }

    #[test]
    fn a_lock_has_at_most_as_many_unlocks_as_the_handle_follows() {
        let more: String = (0..drivebus_model::write_lock::MAX_UNLOCKS - 1)
            .map(|i| {
                format!(
                    "[[unlock]]\nname = \"extra_{i}\"\ngrant = {{ parameter = \"unlock_word\", value = {i} }}\n\
                     allows = [\"controls\"]\nends = [\"lock\"]\nsource = {{ doc = \"m\", line = 9 }}\n"
                )
            })
            .collect();
        assert_eq!(
            messages(RULE, &body(&format!("{LOCK}\n{more}"))),
            ["33 unlocks: a lock has at most 32 (the drive handle follows them in one word)"]
        );
    }

    #[test]
    fn an_unlock_method_may_not_shadow_an_accessor() {
        let lock = LOCK.replace(r#"name = "all""#, r#"name = "word""#);
        assert_eq!(
            messages(RULE, &body(&lock)),
            ["`unlock_word` would collide with the accessor of parameter `unlock_word`"]
        );
    }
}

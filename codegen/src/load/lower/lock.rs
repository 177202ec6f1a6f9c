//! Lowering of `[lock]`, `[[unlock]]` and `[watchdog]` (root file only). Form is checked here
//! (known event and effect names, a grant with exactly one of `value` and `password`, numbers
//! that fit); whether the names resolve is the rule `unlocks_resolve`.

use toml::Spanned;

use super::{Lowering, VALUE_RULE};
use crate::ir;
use crate::load::raw_lock::{RawGrant, RawLock, RawTimeoutAction, RawUnlock, RawWatchdog};

impl Lowering<'_> {
    /// The lock with its unlocks and watchdog. `[[unlock]]` or `[watchdog]` without a `[lock]`
    /// is reported (nothing could end or refuse them).
    pub(super) fn lock(
        &mut self,
        lock: Option<&RawLock>,
        unlocks: &[RawUnlock],
        watchdog: Option<&RawWatchdog>,
    ) -> Option<ir::Lock> {
        let Some(raw) = lock else {
            let stray = unlocks
                .first()
                .map(|u| self.span(&u.name))
                .or(watchdog.map(|w| self.span(&w.timeout)));
            if let Some(span) = stray {
                self.error_help(
                    VALUE_RULE,
                    span,
                    "`[[unlock]]` and `[watchdog]` need a `[lock]`",
                    "`[lock]` names the command that locks and the exception a locked drive answers",
                );
            }
            return None;
        };
        let refusal = self.int_in::<u8>(&raw.refusal, "exception code")?;
        Some(ir::Lock {
            command: raw.command.get_ref().clone(),
            refusal,
            scopes: raw
                .scopes
                .iter()
                .map(|s| ir::LockScope {
                    name: s.get_ref().name.clone(),
                    parameters: s.get_ref().parameters.clone(),
                    rest: s.get_ref().rest,
                    doc: s.get_ref().doc.clone(),
                    span: self.span(s),
                })
                .collect(),
            unlocks: unlocks.iter().filter_map(|u| self.unlock(u)).collect(),
            watchdog: watchdog.and_then(|w| self.watchdog(w)),
            doc: raw.doc.clone(),
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
            span: self.span(&raw.command),
        })
    }

    fn unlock(&mut self, raw: &RawUnlock) -> Option<ir::Unlock> {
        let grant = self.grant(&raw.grant)?;
        let ends = raw.ends.iter().filter_map(|e| self.unlock_end(e)).collect();
        Some(ir::Unlock {
            name: raw.name.get_ref().clone(),
            grant,
            allows: raw.allows.get_ref().clone(),
            requires: raw.requires.as_ref().map(|r| ir::Requirement {
                parameter: r.get_ref().parameter.clone(),
                values: r.get_ref().values.clone(),
                scopes: r
                    .get_ref()
                    .scopes
                    .clone()
                    .unwrap_or_else(|| raw.allows.get_ref().clone()),
                span: self.span(r),
            }),
            ends,
            doc: raw.doc.clone(),
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
            span: self.span(&raw.name),
        })
    }

    fn grant(&mut self, raw: &Spanned<RawGrant>) -> Option<ir::Grant> {
        let g = raw.get_ref();
        let key = match (g.value, &g.password) {
            (Some(value), None) => ir::GrantKey::Value(value),
            (None, Some(password)) => ir::GrantKey::Password(password.clone()),
            _ => {
                let span = self.span(raw);
                self.error_help(
                    VALUE_RULE,
                    span,
                    "a grant needs exactly one of `value` and `password`",
                    "`value` is the raw value written; `password` names the parameter holding the password",
                );
                return None;
            }
        };
        Some(ir::Grant {
            parameter: g.parameter.clone(),
            key,
            span: self.span(raw),
        })
    }

    fn unlock_end(&mut self, raw: &Spanned<String>) -> Option<ir::UnlockEnd> {
        let found = ir::UnlockEnd::ALL
            .iter()
            .find(|(name, _)| name == raw.get_ref())
            .map(|(_, end)| *end);
        if found.is_none() {
            let span = self.span(raw);
            let known: Vec<&str> = ir::UnlockEnd::ALL.iter().map(|(n, _)| *n).collect();
            self.error_help(
                VALUE_RULE,
                span,
                format!("unknown end of an unlock `{}`", raw.get_ref()),
                format!("known: {}", known.join(", ")),
            );
        }
        found
    }

    fn watchdog(&mut self, raw: &RawWatchdog) -> Option<ir::Watchdog> {
        let actions = raw
            .actions
            .get_ref()
            .iter()
            .filter_map(|a| self.timeout_action(a))
            .collect();
        Some(ir::Watchdog {
            timeout: raw.timeout.get_ref().clone(),
            action: raw.action.get_ref().clone(),
            actions,
            acts_with: raw.acts_with.clone(),
            doc: raw.doc.clone(),
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
            span: self.span(&raw.timeout),
        })
    }

    fn timeout_action(&mut self, raw: &Spanned<RawTimeoutAction>) -> Option<ir::TimeoutAction> {
        let a = raw.get_ref();
        let span = self.span(raw);
        let does = match (a.does.as_str(), a.fault) {
            ("disabled", None) => ir::TimeoutEffect::Disabled,
            ("coast", None) => ir::TimeoutEffect::Coast,
            ("quick_stop", None) => ir::TimeoutEffect::QuickStop,
            ("fault", Some(code)) => match u16::try_from(code) {
                Ok(code) => ir::TimeoutEffect::Fault(code),
                Err(_) => {
                    self.error(
                        VALUE_RULE,
                        span,
                        format!("fault code {code} is out of range"),
                    );
                    return None;
                }
            },
            (does, fault) => {
                let message = match (does, fault) {
                    ("fault", None) => "`does = \"fault\"` needs `fault = <code>`".to_string(),
                    ("disabled" | "coast" | "quick_stop", Some(_)) => {
                        format!("`fault` belongs to `does = \"fault\"`, not `{does}`")
                    }
                    _ => format!("unknown timeout action `{does}`"),
                };
                self.error_help(
                    VALUE_RULE,
                    span,
                    message,
                    "known: disabled, coast, quick_stop, and fault with `fault = <code>`",
                );
                return None;
            }
        };
        Some(ir::TimeoutAction {
            value: a.value,
            does,
            span,
        })
    }
}

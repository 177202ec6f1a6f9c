//! Lowering of `[[ramp]]` (root file only). The form of each slope is checked here (`{ time }`,
//! `{ rate }` or `{ speed, time }`); whether the names resolve is the rule `ramps_resolve`.

use toml::Spanned;

use super::{Lowering, VALUE_RULE};
use crate::ir;
use crate::load::raw_ramp::{RawRamp, RawSlope};

impl Lowering<'_> {
    /// A ramp, or `None` (reported) when a slope has no valid form.
    pub(super) fn ramp(&mut self, raw: &RawRamp) -> Option<ir::Ramp> {
        let up = self.slope(&raw.up);
        let down = self.slope(&raw.down);
        Some(ir::Ramp {
            setpoint: raw.setpoint.get_ref().clone(),
            up: up?,
            down: down?,
            full_scale: raw.full_scale.clone(),
            enable: raw.enable.clone(),
            polarity: raw.polarity.as_ref().map(|p| ir::Polarity {
                parameter: p.parameter.clone(),
                bit: p.bit,
            }),
            doc: raw.doc.clone(),
            source: raw.source.as_ref().and_then(|c| self.citation(c)),
            span: self.span(&raw.setpoint),
        })
    }

    fn slope(&mut self, raw: &Spanned<RawSlope>) -> Option<ir::Slope> {
        let s = raw.get_ref();
        if s.per
            .as_deref()
            .is_some_and(|p| ir::per_second(p).is_none())
            || (s.per.is_some() && s.rate.is_none())
        {
            let span = self.span(raw);
            self.error_help(
                VALUE_RULE,
                span,
                "`per` is the time unit of a `{ rate }`: `ms` or `s`",
                "`{ rate = \"acceleration\", per = \"ms\" }`: setpoint units per millisecond",
            );
            return None;
        }
        let slope = match (&s.time, &s.rate, &s.speed) {
            (Some(time), None, None) => ir::Slope::Time { time: time.clone() },
            (None, Some(rate), None) => ir::Slope::Rate {
                rate: rate.clone(),
                per: s.per.clone(),
            },
            (Some(time), None, Some(speed)) => ir::Slope::Delta {
                speed: speed.clone(),
                time: time.clone(),
            },
            _ => {
                let span = self.span(raw);
                self.error_help(
                    VALUE_RULE,
                    span,
                    "a ramp slope is `{ time }`, `{ rate }` or `{ speed, time }`",
                    "`time`: from 0 to `full_scale`; `rate`: setpoint units per second (or per `per`); \
                     `speed` and `time`: that speed change in that time",
                );
                return None;
            }
        };
        Some(slope)
    }
}

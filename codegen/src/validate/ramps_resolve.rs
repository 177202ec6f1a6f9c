//! Ramps resolve: each `[[ramp]]` names an integer setpoint shaped by no other ramp, integer
//! slope, full-scale, enable and polarity parameters, a polarity bit within its parameter, ramp
//! times in `ms` or `s`, and a `full_scale` exactly when a slope is a time from 0 to it.

use std::collections::BTreeSet;

use crate::diagnostic::Diagnostic;
use crate::ir::{per_second, Device, Ramp};

const RULE: &str = super::rule_name(module_path!());

/// Reports ramps that name nothing usable.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let mut setpoints = BTreeSet::new();
    for ramp in &device.ramps {
        let mut report = |message: String| {
            out.push(Diagnostic::error(RULE, ramp.span.clone(), message));
        };
        if !setpoints.insert(ramp.setpoint.as_str()) {
            report(format!("setpoint `{}` has two ramps", ramp.setpoint));
        }
        for (role, name) in named(ramp) {
            integer(device, role, name, &mut report);
        }
        let times: BTreeSet<&str> = ramp.slopes().iter().filter_map(|s| s.time()).collect();
        for time in times {
            time_unit(device, time, &mut report);
        }
        if let Some(polarity) = &ramp.polarity {
            let bits = device
                .parameter(&polarity.parameter)
                .map(|p| u32::from(p.data_type.bytes()) * 8);
            if bits.is_some_and(|bits| polarity.bit >= bits) {
                report(format!(
                    "polarity bit {} does not fit `{}`",
                    polarity.bit, polarity.parameter
                ));
            }
        }
        match (ramp.needs_full_scale(), &ramp.full_scale) {
            (true, None) => report(format!(
                "the ramp of `{}` gives a time from 0 to full scale but no `full_scale`",
                ramp.setpoint
            )),
            (false, Some(full_scale)) => report(format!(
                "`full_scale = \"{full_scale}\"` is used by `{{ time }}` slopes only"
            )),
            _ => {}
        }
    }
    out
}

/// Every parameter a ramp names, with its role.
fn named(ramp: &Ramp) -> Vec<(&'static str, &str)> {
    let mut named = vec![("setpoint", ramp.setpoint.as_str())];
    named.extend(
        ramp.slopes()
            .iter()
            .flat_map(|s| s.parameters())
            .map(|p| ("slope", p)),
    );
    named.extend(ramp.full_scale.as_deref().map(|p| ("full scale", p)));
    named.extend(ramp.enable.as_deref().map(|p| ("enable", p)));
    named.extend(
        ramp.polarity
            .as_ref()
            .map(|p| ("polarity", p.parameter.as_str())),
    );
    named
}

fn integer(device: &Device, role: &str, name: &str, report: &mut impl FnMut(String)) {
    match device.parameter(name) {
        None => report(format!("the ramp's {role} `{name}` is not a parameter")),
        Some(p) if !p.data_type.is_integer() => {
            report(format!("the ramp's {role} `{name}` is not an integer"));
        }
        Some(_) => {}
    }
}

fn time_unit(device: &Device, name: &str, report: &mut impl FnMut(String)) {
    let Some(p) = device.parameter(name) else {
        return;
    };
    if p.unit.as_deref().and_then(per_second).is_none() {
        report(format!(
            "the ramp time `{name}` has unit {}; a ramp time is in `ms` or `s`",
            p.unit
                .as_deref()
                .map_or("none".to_string(), |u| format!("`{u}`"))
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::{device, messages};

    /// A Lafert-style drive: a setpoint, ramp times in ms, a full scale and a ramp enable.
    const PARAMETERS: &str = r#"
[[parameter]]
name = "speed_setpoint"
type = "i16"
unit = "rpm"
modbus = { table = "holding", address = 0x42, access = "rw" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "full_scale_velocity"
type = "u16"
unit = "rpm"
modbus = { table = "holding", address = 3, access = "rw" }
source = { doc = "m", line = 2 }

[[parameter]]
name = "speed_ramp_up"
type = "u16"
unit = "ms"
modbus = { table = "holding", address = 0x40, access = "rw" }
source = { doc = "m", line = 3 }

[[parameter]]
name = "speed_ramp_down"
type = "u16"
unit = "ms"
modbus = { table = "holding", address = 0x41, access = "rw" }
source = { doc = "m", line = 4 }

[[parameter]]
name = "ramp_enable"
type = "u16"
modbus = { table = "holding", address = 0x3F, access = "rw" }
source = { doc = "m", line = 5 }

[[parameter]]
name = "label"
type = "string"
length = 4
modbus = { table = "holding", address = 0x50, words = 2, access = "rw" }
source = { doc = "m", line = 6 }
"#;

    const RAMP: &str = r#"
[[ramp]]
setpoint = "speed_setpoint"
up = { time = "speed_ramp_up" }
down = { time = "speed_ramp_down" }
full_scale = "full_scale_velocity"
enable = "ramp_enable"
source = { doc = "m", line = 7 }
"#;

    fn body(ramp: &str) -> String {
        format!("{ramp}\n{PARAMETERS}")
    }

    #[test]
    fn a_complete_ramp_resolves() {
        let device = device(&body(RAMP));
        assert_eq!(device.ramps.len(), 1);
        assert!(device.ramps[0].needs_full_scale());
        assert!(messages(RULE, &body(RAMP)).is_empty());
    }

    #[test]
    fn unknown_and_non_integer_names_are_reported() {
        let ramp = RAMP
            .replace(r#"enable = "ramp_enable""#, r#"enable = "ramp_on""#)
            .replace(
                r#"full_scale = "full_scale_velocity""#,
                r#"full_scale = "label""#,
            );
        assert_eq!(
            messages(RULE, &body(&ramp)),
            [
                "the ramp's full scale `label` is not an integer",
                "the ramp's enable `ramp_on` is not a parameter",
            ]
        );
    }

    #[test]
    fn a_polarity_names_an_integer_and_a_bit_within_it() {
        let with = |polarity: &str| {
            RAMP.replace("enable = ", &format!("polarity = {polarity}\nenable = "))
        };
        let fits = with(r#"{ parameter = "ramp_enable", bit = 0 }"#);
        assert!(messages(RULE, &body(&fits)).is_empty());
        assert_eq!(
            device(&body(&fits)).ramps[0]
                .polarity
                .as_ref()
                .map(|p| p.bit),
            Some(0)
        );
        assert_eq!(
            messages(
                RULE,
                &body(&with(r#"{ parameter = "ramp_enable", bit = 16 }"#))
            ),
            ["polarity bit 16 does not fit `ramp_enable`"]
        );
        assert_eq!(
            messages(
                RULE,
                &body(&with(r#"{ parameter = "label", bit = 0 }"#))
            ),
            ["the ramp's polarity `label` is not an integer"]
        );
    }

    #[test]
    fn ramp_times_are_in_ms_or_s() {
        let ramp = RAMP.replace(
            r#"down = { time = "speed_ramp_down" }"#,
            r#"down = { speed = "speed_ramp_down", time = "full_scale_velocity" }"#,
        );
        assert_eq!(
            messages(RULE, &body(&ramp)),
            ["the ramp time `full_scale_velocity` has unit `rpm`; a ramp time is in `ms` or `s`"]
        );
    }

    #[test]
    fn full_scale_goes_with_time_slopes_and_a_setpoint_has_one_ramp() {
        let without = RAMP.replace("full_scale = \"full_scale_velocity\"\n", "");
        assert_eq!(
            messages(RULE, &body(&without)),
            ["the ramp of `speed_setpoint` gives a time from 0 to full scale but no `full_scale`"]
        );
        let rates = RAMP
            .replace(
                r#"{ time = "speed_ramp_up" }"#,
                r#"{ rate = "speed_ramp_up" }"#,
            )
            .replace(
                r#"{ time = "speed_ramp_down" }"#,
                r#"{ rate = "speed_ramp_down" }"#,
            );
        assert_eq!(
            messages(RULE, &body(&rates)),
            ["`full_scale = \"full_scale_velocity\"` is used by `{ time }` slopes only"]
        );
        assert_eq!(
            messages(RULE, &body(&format!("{RAMP}{RAMP}"))),
            ["setpoint `speed_setpoint` has two ramps"]
        );
    }

    #[test]
    fn a_rate_may_be_given_per_millisecond() {
        let per_ms = RAMP
            .replace(
                r#"{ time = "speed_ramp_up" }"#,
                r#"{ rate = "speed_ramp_up", per = "ms" }"#,
            )
            .replace(
                r#"{ time = "speed_ramp_down" }"#,
                r#"{ rate = "speed_ramp_down" }"#,
            )
            .replace("full_scale = \"full_scale_velocity\"\n", "");
        let device = device(&body(&per_ms));
        assert_eq!(
            device.ramps[0].up,
            crate::ir::Slope::Rate {
                rate: "speed_ramp_up".into(),
                per: Some("ms".into())
            }
        );
        assert_eq!(
            device.ramps[0].down,
            crate::ir::Slope::Rate {
                rate: "speed_ramp_down".into(),
                per: None
            }
        );
        let per_minute = per_ms.replace(r#"per = "ms""#, r#"per = "min""#);
        assert_eq!(
            messages("values_are_well_formed", &body(&per_minute)),
            ["`per` is the time unit of a `{ rate }`: `ms` or `s`"]
        );
        let per_without_rate = RAMP.replace(
            r#"{ time = "speed_ramp_up" }"#,
            r#"{ time = "speed_ramp_up", per = "ms" }"#,
        );
        assert_eq!(
            messages("values_are_well_formed", &body(&per_without_rate)),
            ["`per` is the time unit of a `{ rate }`: `ms` or `s`"]
        );
    }
}

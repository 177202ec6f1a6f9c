//! Every declared SRDO has non-zero SCT and SRVT, SRVT below SCT (the runtime's
//! `SrdoTiming` rule), and an SRVT of at most 255 ms, the one byte the safety signature takes.

use drivebus_model::canopen::srdo::{SrdoError, SrdoTiming};

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Mapping, SrdoDefaults};

const RULE: &str = super::rule_name(module_path!());

/// Reports times the runtime would refuse or the signature could not hold.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device.srdos().filter_map(|(m, s)| problem(m, s)).collect()
}

fn problem(m: &Mapping, s: &SrdoDefaults) -> Option<Diagnostic> {
    let why = match SrdoTiming::from_millis(s.sct_ms, s.srvt_ms) {
        Err(SrdoError::BadConfiguration(why)) => why,
        _ if s.srvt_ms > 255 => "SRVT above 255 ms does not fit the signature's byte",
        _ => return None,
    };
    Some(
        Diagnostic::error(RULE, m.span.clone(), format!("SRDO `{}`: {why}", m.name))
            .help("give `sct_ms` and `srvt_ms` as the manual's communication object does"),
    )
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    fn srdo(sct: u32, srvt: u32) -> String {
        format!("[[parameter]]\nname = \"w\"\ntype = \"u8\"\ncanopen = {{ index = 0x6620, subindex = 1 }}\nsource = {{ doc = \"m\", line = 1 }}\n[[srdo]]\nname = \"s\"\nnumber = 1\ndirection = \"rx\"\nsct_ms = {sct}\nsrvt_ms = {srvt}\ncob_ids = [0x101, 0x102]\nentries = [\"w\", \"w\"]\n")
    }

    #[test]
    fn the_manual_defaults_are_fine() {
        assert!(messages(RULE, &srdo(50, 20)).is_empty());
    }

    #[test]
    fn bad_times_are_reported() {
        assert_eq!(
            messages(RULE, &srdo(20, 20)),
            ["SRDO `s`: SRVT must be lower than SCT"]
        );
        assert_eq!(
            messages(RULE, &srdo(1000, 300)),
            ["SRDO `s`: SRVT above 255 ms does not fit the signature's byte"]
        );
    }
}

//! Validation: one pass per rule, each in its own file named as the rule it enforces.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

mod access_matches_functions;
mod addresses_do_not_overlap;
mod bit_fields_fit;
mod defaults_within_range;
mod enum_values_fit_type;
mod names_are_unique;
mod parameters_have_addresses;
mod pdo_entries_are_mappable;
mod pdo_mappings_fit_eight_bytes;
mod pdo_numbers_are_unique;
mod ranges_fit_type;
mod records_hold_their_members;
mod references_resolve;
mod rs232_values_fit_a_telegram;
pub(crate) mod scale_inputs_exist;
mod scale_is_representable;
mod state_machines_resolve;
mod strings_have_length;
mod units_are_known;
mod value_types_are_consistent;
mod values_cite_sources;
mod words_fit_type;

/// A validation pass: reads the IR, returns what is wrong.
pub type Pass = fn(&Device) -> Vec<Diagnostic>;

/// Every pass, by rule name, in the order they run.
pub const PASSES: &[(&str, Pass)] = &[
    ("references_resolve", references_resolve::check),
    ("names_are_unique", names_are_unique::check),
    (
        "parameters_have_addresses",
        parameters_have_addresses::check,
    ),
    ("values_cite_sources", values_cite_sources::check),
    ("units_are_known", units_are_known::check),
    ("strings_have_length", strings_have_length::check),
    (
        "value_types_are_consistent",
        value_types_are_consistent::check,
    ),
    ("ranges_fit_type", ranges_fit_type::check),
    ("defaults_within_range", defaults_within_range::check),
    ("enum_values_fit_type", enum_values_fit_type::check),
    ("bit_fields_fit", bit_fields_fit::check),
    ("scale_is_representable", scale_is_representable::check),
    ("scale_inputs_exist", scale_inputs_exist::check),
    ("words_fit_type", words_fit_type::check),
    (
        "rs232_values_fit_a_telegram",
        rs232_values_fit_a_telegram::check,
    ),
    ("addresses_do_not_overlap", addresses_do_not_overlap::check),
    ("access_matches_functions", access_matches_functions::check),
    (
        "records_hold_their_members",
        records_hold_their_members::check,
    ),
    ("state_machines_resolve", state_machines_resolve::check),
    ("pdo_entries_are_mappable", pdo_entries_are_mappable::check),
    (
        "pdo_mappings_fit_eight_bytes",
        pdo_mappings_fit_eight_bytes::check,
    ),
    ("pdo_numbers_are_unique", pdo_numbers_are_unique::check),
];

/// Runs every pass.
pub fn validate(device: &Device) -> Vec<Diagnostic> {
    PASSES.iter().flat_map(|(_, pass)| pass(device)).collect()
}

#[cfg(test)]
pub(crate) mod test_support {
    //! Runs the whole pipeline on a description written inline.

    use crate::diagnostic::Diagnostic;

    /// A minimal valid device header; tests append tables to it.
    pub const HEADER: &str = r#"format = 1
[device]
name = "Test"
handle = "Test"
[[source]]
id = "m"
file = "manual.txt"
title = "Manual"
"#;

    /// The whole check of `HEADER + body`.
    pub fn checked(body: &str) -> crate::Checked {
        let dir =
            std::env::temp_dir().join(format!("drivegen-test-{}-{}", std::process::id(), unique()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("device.toml");
        std::fs::write(&path, format!("{HEADER}{body}")).unwrap();
        let checked = crate::check(&path);
        std::fs::remove_dir_all(&dir).unwrap();
        checked
    }

    /// Diagnostics of `HEADER + body`, keeping only those of `rule`.
    pub fn diagnostics(rule: &str, body: &str) -> Vec<Diagnostic> {
        checked(body)
            .diagnostics
            .into_iter()
            .filter(|d| d.rule == rule)
            .collect()
    }

    /// The device model of `HEADER + body`, which must be valid.
    pub fn device(body: &str) -> crate::ir::Device {
        let checked = checked(body);
        match checked.device {
            Some(device) => device,
            None => panic!("invalid test description:\n{}", checked.render()),
        }
    }

    fn unique() -> u64 {
        use std::sync::atomic::{AtomicU64, Ordering};
        static NEXT: AtomicU64 = AtomicU64::new(0);
        NEXT.fetch_add(1, Ordering::Relaxed)
    }

    /// Messages of the diagnostics of `rule`.
    pub fn messages(rule: &str, body: &str) -> Vec<String> {
        diagnostics(rule, body)
            .into_iter()
            .map(|d| d.message)
            .collect()
    }
}

//! Validation: one pass per rule, each in its own file named as the rule it enforces.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

mod access_matches_functions;
mod addresses_do_not_overlap;
mod bit_codes_are_enum_values;
mod bit_fields_fit;
mod bounds_resolve;
pub(crate) mod canopen_has_mandatory_objects;
mod combined_commands_name_a_command;
mod commands_share_a_register;
mod communication_loss_resolves;
mod defaults_within_range;
mod enum_values_fit_type;
mod identity_names_a_parameter;
mod identity_values_fit;
mod indexed_names_are_unique;
mod input_reads_alias_holding;
mod lss_has_an_lss_address;
mod manual_names_are_search_aliases;
mod mapping_entries_are_mappable;
mod mapping_numbers_are_unique;
mod mappings_fit_a_frame;
mod models_give_constants;
mod names_are_unique;
mod parameters_have_addresses;
mod ramps_resolve;
mod ranges_fit_type;
mod read_blocks_are_described;
mod records_hold_their_members;
mod references_resolve;
mod rs232_values_fit_a_telegram;
pub(crate) mod scale_inputs_exist;
mod scale_is_representable;
mod srdo_timings_are_valid;
mod state_machines_resolve;
mod stops_are_always_sendable;
mod strings_have_length;
mod units_are_known;
mod unlocks_resolve;
mod value_types_are_consistent;
mod values_cite_sources;
mod variant_selectors_resolve;
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
    ("bounds_resolve", bounds_resolve::check),
    ("enum_values_fit_type", enum_values_fit_type::check),
    ("bit_fields_fit", bit_fields_fit::check),
    (
        "bit_codes_are_enum_values",
        bit_codes_are_enum_values::check,
    ),
    ("scale_is_representable", scale_is_representable::check),
    ("models_give_constants", models_give_constants::check),
    ("scale_inputs_exist", scale_inputs_exist::check),
    ("words_fit_type", words_fit_type::check),
    (
        "rs232_values_fit_a_telegram",
        rs232_values_fit_a_telegram::check,
    ),
    ("addresses_do_not_overlap", addresses_do_not_overlap::check),
    ("access_matches_functions", access_matches_functions::check),
    (
        "read_blocks_are_described",
        read_blocks_are_described::check,
    ),
    (
        "records_hold_their_members",
        records_hold_their_members::check,
    ),
    ("state_machines_resolve", state_machines_resolve::check),
    (
        "mapping_entries_are_mappable",
        mapping_entries_are_mappable::check,
    ),
    ("mappings_fit_a_frame", mappings_fit_a_frame::check),
    ("srdo_timings_are_valid", srdo_timings_are_valid::check),
    (
        "mapping_numbers_are_unique",
        mapping_numbers_are_unique::check,
    ),
    ("indexed_names_are_unique", indexed_names_are_unique::check),
    (
        "identity_names_a_parameter",
        identity_names_a_parameter::check,
    ),
    ("identity_values_fit", identity_values_fit::check),
    (
        "canopen_has_mandatory_objects",
        canopen_has_mandatory_objects::check,
    ),
    ("lss_has_an_lss_address", lss_has_an_lss_address::check),
    (
        "variant_selectors_resolve",
        variant_selectors_resolve::check,
    ),
    (
        "manual_names_are_search_aliases",
        manual_names_are_search_aliases::check,
    ),
    ("unlocks_resolve", unlocks_resolve::check),
    ("ramps_resolve", ramps_resolve::check),
    (
        "stops_are_always_sendable",
        stops_are_always_sendable::check,
    ),
    (
        "communication_loss_resolves",
        communication_loss_resolves::check,
    ),
    (
        "input_reads_alias_holding",
        input_reads_alias_holding::check,
    ),
    (
        "combined_commands_name_a_command",
        combined_commands_name_a_command::check,
    ),
];

/// Runs every pass.
pub fn validate(device: &Device) -> Vec<Diagnostic> {
    PASSES.iter().flat_map(|(_, pass)| pass(device)).collect()
}

/// Inline descriptions through the whole pipeline, for the tests of every pass.
#[cfg(test)]
pub(crate) use crate::test_support;

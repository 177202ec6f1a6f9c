//! Validation: one pass per rule, each in its own file named as the rule it enforces.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

// A helper of `addresses_do_not_overlap`, not a rule.
mod commands_share_a_register;

/// A validation pass: reads the IR, returns what is wrong.
pub type Pass = fn(&Device) -> Vec<Diagnostic>;

/// Declares each rule's module and lists its pass under the module's name, so that a rule is
/// named once, by its file: `PASSES`, the UI test's table and the rule's own diagnostics
/// ([`rule_name`]) all read that name.
macro_rules! passes {
    ($($vis:vis $rule:ident,)*) => {
        $( $vis mod $rule; )*

        /// Every pass, by rule name, in the order they run.
        pub const PASSES: &[(&str, Pass)] = &[ $( (stringify!($rule), $rule::check) ),* ];
    };
}

passes![
    references_resolve,
    names_are_unique,
    parameters_have_addresses,
    values_cite_sources,
    units_are_known,
    strings_have_length,
    value_types_are_consistent,
    ranges_fit_type,
    defaults_within_range,
    bounds_resolve,
    enum_values_fit_type,
    bit_fields_fit,
    bit_codes_are_enum_values,
    scale_is_representable,
    models_give_constants,
    pub(crate) scale_inputs_exist,
    words_fit_type,
    rs232_values_fit_a_telegram,
    addresses_do_not_overlap,
    access_matches_functions,
    read_blocks_are_described,
    read_backs_share_their_register,
    records_hold_their_members,
    state_machines_resolve,
    mapping_entries_are_mappable,
    mappings_fit_a_frame,
    srdo_timings_are_valid,
    mapping_numbers_are_unique,
    indexed_names_are_unique,
    identity_names_a_parameter,
    identity_values_fit,
    pub(crate) canopen_has_mandatory_objects,
    lss_has_an_lss_address,
    variant_selectors_resolve,
    manual_names_are_search_aliases,
    unlocks_resolve,
    ramps_resolve,
    stops_are_always_sendable,
    communication_loss_resolves,
    input_reads_alias_holding,
    combined_commands_name_a_command,
];

/// The rule a validation module enforces: the last segment of its `module_path!()`, which is its
/// file's name (`const RULE: &str = super::rule_name(module_path!());`).
pub(crate) const fn rule_name(module_path: &'static str) -> &'static str {
    let bytes = module_path.as_bytes();
    let mut start = bytes.len();
    while start > 0 && bytes[start - 1] != b':' {
        start -= 1;
    }
    let (_, name) = bytes.split_at(start);
    match core::str::from_utf8(name) {
        Ok(name) => name,
        Err(_) => module_path,
    }
}

/// Runs every pass.
pub fn validate(device: &Device) -> Vec<Diagnostic> {
    PASSES.iter().flat_map(|(_, pass)| pass(device)).collect()
}

/// Inline descriptions through the whole pipeline, for the tests of every pass.
#[cfg(test)]
pub(crate) use crate::test_support;

#[cfg(test)]
mod tests {
    use super::{rule_name, test_support, PASSES};

    #[test]
    fn a_rule_is_named_by_its_module() {
        assert_eq!(
            rule_name("drivegen::validate::units_are_known"),
            "units_are_known"
        );
        assert_eq!(rule_name("bare"), "bare");
        let (first, _) = PASSES[0];
        assert_eq!(first, "references_resolve");
        let unknown_unit = test_support::messages(
            "units_are_known",
            "[[parameter]]\nname = \"x\"\ntype = \"u16\"\nunit = \"parsec\"\nmodbus = { table = \"holding\", address = 0, access = \"r\" }\n",
        );
        assert!(
            !unknown_unit.is_empty(),
            "the rule reports under its file's name"
        );
    }
}

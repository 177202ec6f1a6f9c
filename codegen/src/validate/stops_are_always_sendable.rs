//! A parameter whose writes stop the drive (`stops`) can always be sent: it is an integer with a
//! writable address, one address for every variant (a stop is sent even while the drive's
//! variant is unknown), and its patterns fit its type.

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Parameter, StopWrites};

const RULE: &str = super::rule_name(module_path!());

/// Reports stop writes that could not always be sent.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .parameters
        .iter()
        .filter_map(|p| Some((p, p.stops.as_ref()?)))
        .filter_map(|(p, stops)| {
            let problem = problem(p, stops)?;
            Some(Diagnostic::error(RULE, stops.span.clone(), problem))
        })
        .collect()
}

fn problem(p: &Parameter, stops: &StopWrites) -> Option<String> {
    let name = &p.name;
    if !p.data_type.is_integer() {
        return Some(format!("`{name}` stops the drive but is not an integer"));
    }
    let writable = || {
        let objects = p.canopen.iter().chain(&p.rs232);
        let modbus = p
            .modbus
            .iter()
            .filter(|a| a.access.write)
            .map(|a| &a.variant);
        modbus.chain(objects.filter(|a| a.access.write).map(|a| &a.variant))
    };
    if writable().next().is_none() {
        return Some(format!("`{name}` stops the drive but cannot be written"));
    }
    if !p.variants.is_empty() || writable().any(Option::is_some) {
        return Some(format!(
            "`{name}` stops the drive but its address depends on the variant: a stop must reach \
             the drive in every variant"
        ));
    }
    let width_mask = u64::MAX >> (64 - 8 * u32::from(p.data_type.bytes()).min(8));
    stops.patterns.iter().flatten().find_map(|pattern| {
        (pattern.mask & !width_mask != 0 || pattern.value & !pattern.mask != 0).then(|| {
            format!(
                "`{name}`: the stop pattern mask {:#x}, value {:#x} does not fit: the mask must \
                 lie within the {}-bit type and the value within the mask",
                pattern.mask,
                pattern.value,
                8 * p.data_type.bytes()
            )
        })
    })
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    fn body(stops: &str, data_type: &str, address: &str) -> String {
        format!(
            "[[parameter]]\nname = \"controlword\"\ntype = \"{data_type}\"\nstops = {stops}\n\
             {address}\nsource = {{ doc = \"m\", line = 1 }}\n"
        )
    }

    const WRITABLE: &str = "canopen = { index = 0x6040, access = \"rw\" }";

    #[test]
    fn a_fitting_pattern_and_a_stop_command_pass() {
        let pattern = "[{ mask = 0x0008, value = 0 }, { mask = 0x0100, value = 0x0100 }]";
        assert!(messages(super::RULE, &body(pattern, "u16", WRITABLE)).is_empty());
        assert!(messages(super::RULE, &body("true", "u16", WRITABLE)).is_empty());
    }

    #[test]
    fn a_pattern_beyond_the_type_or_the_mask_is_reported() {
        let wide = "[{ mask = 0x10000, value = 0 }]";
        let outside = "[{ mask = 0x0008, value = 0x0001 }]";
        for pattern in [wide, outside] {
            let found = messages(super::RULE, &body(pattern, "u16", WRITABLE));
            assert_eq!(found.len(), 1, "{pattern}: {found:?}");
            assert!(found[0].contains("does not fit"), "{found:?}");
        }
    }

    #[test]
    fn a_read_only_or_text_stop_is_reported() {
        let read_only = "canopen = { index = 0x6040, access = \"ro\" }";
        assert_eq!(
            messages(super::RULE, &body("true", "u16", read_only)),
            ["`controlword` stops the drive but cannot be written"]
        );
        assert_eq!(
            messages(super::RULE, &body("true", "f32", WRITABLE)),
            ["`controlword` stops the drive but is not an integer"]
        );
    }

    #[test]
    fn a_stop_whose_address_depends_on_the_variant_is_reported() {
        let per_variant = "[[variant]]\nname = \"a\"\n[[variant]]\nname = \"b\"\n\
            [[parameter]]\nname = \"stop\"\ntype = \"u16\"\nstops = true\n\
            modbus = [{ table = \"holding\", address = 1, access = \"w\", variant = \"a\" }, \
                      { table = \"holding\", address = 2, access = \"w\", variant = \"b\" }]\n\
            source = { doc = \"m\", line = 1 }\n";
        let found = messages(super::RULE, per_variant);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].contains("depends on the variant"), "{found:?}");
    }
}

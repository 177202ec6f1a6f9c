//! Variants selected at run time (`selected_by`) name one readable integer parameter that exists
//! in every variant at one address, each variant with a value of its own that fits its type.

use std::collections::BTreeMap;

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Parameter, Variant};

const RULE: &str = super::rule_name(module_path!());

/// Reports selectors that are partial, mixed, unresolvable, unreadable or ambiguous.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let Some(first) = device.variants.iter().find_map(|v| v.selected_by.as_ref()) else {
        return Vec::new();
    };
    let mut out: Vec<Diagnostic> = device
        .variants
        .iter()
        .filter_map(|v| consistency(v, &first.parameter))
        .collect();
    match device.parameter(&first.parameter) {
        None => out.push(Diagnostic::error(
            RULE,
            first.span.clone(),
            format!(
                "`selected_by` names `{}`, which is not a parameter",
                first.parameter
            ),
        )),
        Some(p) => {
            out.extend(unusable(p).map(|why| {
                Diagnostic::error(
                    RULE,
                    first.span.clone(),
                    format!("`{}` cannot select the variant: {why}", p.name),
                )
            }));
            out.extend(value_problems(device, p));
        }
    }
    out
}

/// A variant without a selector, or with one naming another parameter.
fn consistency(variant: &Variant, parameter: &str) -> Option<Diagnostic> {
    match &variant.selected_by {
        None => Some(
            Diagnostic::error(
                RULE,
                variant.span.clone(),
                format!("variant `{}` has no `selected_by`", variant.name),
            )
            .help("either every variant says how the drive reports it, or none does"),
        ),
        Some(s) if s.parameter != parameter => Some(Diagnostic::error(
            RULE,
            s.span.clone(),
            format!(
                "variant `{}` is selected by `{}`, the others by `{parameter}`",
                variant.name, s.parameter
            ),
        )),
        Some(_) => None,
    }
}

/// Why `p` cannot be read before the variant is known, if it cannot.
fn unusable(p: &Parameter) -> Option<&'static str> {
    if !p.data_type.is_integer() {
        Some("it is not an integer")
    } else if !p.variants.is_empty() {
        Some("it does not exist in every variant")
    } else if p.modbus.iter().any(|a| a.variant.is_some())
        || p.canopen.iter().any(|a| a.variant.is_some())
    {
        Some("its address depends on the variant")
    } else if !(p.modbus.iter().any(|a| a.access.read) || p.canopen.iter().any(|a| a.access.read)) {
        Some("it is not readable")
    } else {
        None
    }
}

/// Values that repeat or do not fit the parameter's type.
fn value_problems<'a>(
    device: &'a Device,
    p: &'a Parameter,
) -> impl Iterator<Item = Diagnostic> + 'a {
    let mut seen: BTreeMap<i64, &str> = BTreeMap::new();
    let bounds = p.data_type.integer_bounds();
    device.variants.iter().filter_map(move |v| {
        let s = v.selected_by.as_ref()?;
        let message = if let Some(other) = seen.insert(s.value, &v.name) {
            format!(
                "variants `{other}` and `{}` are both selected by {}",
                v.name, s.value
            )
        } else if bounds.is_some_and(|(lo, hi)| !(lo..=hi).contains(&i128::from(s.value))) {
            format!(
                "{} does not fit `{}` ({})",
                s.value,
                p.name,
                p.data_type.name()
            )
        } else {
            return None;
        };
        Some(Diagnostic::error(RULE, s.span.clone(), message))
    })
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::{device, messages};

    const SELECTOR: &str = r#"
[[parameter]]
name = "configuration"
type = "u16"
modbus = { table = "holding", address = 50, access = "r" }
source = { doc = "m", line = 1 }
"#;

    fn variants(a: &str, b: &str) -> String {
        format!(
            "[[variant]]\nname = \"pc400\"\nselected_by = {a}\n[[variant]]\nname = \"pc507\"\nselected_by = {b}\n{SELECTOR}"
        )
    }

    #[test]
    fn a_complete_selector_resolves() {
        let body = variants(
            r#"{ parameter = "configuration", value = 400 }"#,
            r#"{ parameter = "configuration", value = 507 }"#,
        );
        let device = device(&body);
        let (parameter, values) = device.variant_selection().unwrap();
        assert_eq!(parameter.name, "configuration");
        assert_eq!(values, [(0, 400), (1, 507)]);
    }

    #[test]
    fn repeated_and_oversized_values_are_reported() {
        let body = variants(
            r#"{ parameter = "configuration", value = 400 }"#,
            r#"{ parameter = "configuration", value = 400 }"#,
        );
        assert_eq!(
            messages(RULE, &body),
            ["variants `pc400` and `pc507` are both selected by 400"]
        );
        let body = variants(
            r#"{ parameter = "configuration", value = 400 }"#,
            r#"{ parameter = "configuration", value = 70000 }"#,
        );
        assert_eq!(
            messages(RULE, &body),
            ["70000 does not fit `configuration` (u16)"]
        );
    }

    #[test]
    fn a_partial_or_mixed_selection_is_reported() {
        let body = format!(
            "[[variant]]\nname = \"a\"\nselected_by = {{ parameter = \"configuration\", value = 1 }}\n[[variant]]\nname = \"b\"\n{SELECTOR}"
        );
        assert_eq!(
            messages(RULE, &body),
            ["variant `b` has no `selected_by`"]
        );
        let body = variants(
            r#"{ parameter = "configuration", value = 400 }"#,
            r#"{ parameter = "other", value = 507 }"#,
        );
        assert_eq!(
            messages(RULE, &body),
            ["variant `pc507` is selected by `other`, the others by `configuration`"]
        );
    }

    #[test]
    fn the_selector_must_be_readable_in_every_variant() {
        let body = variants(
            r#"{ parameter = "configuration", value = 400 }"#,
            r#"{ parameter = "configuration", value = 507 }"#,
        )
        .replace(r#"access = "r""#, r#"access = "rw", variant = "pc400""#);
        assert_eq!(
            messages(RULE, &body),
            ["`configuration` cannot select the variant: its address depends on the variant"]
        );
        let body = variants(
            r#"{ parameter = "missing", value = 400 }"#,
            r#"{ parameter = "missing", value = 507 }"#,
        );
        assert_eq!(
            messages(RULE, &body),
            ["`selected_by` names `missing`, which is not a parameter"]
        );
    }
}

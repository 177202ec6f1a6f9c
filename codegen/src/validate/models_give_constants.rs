//! Per-model constants are complete and unambiguous: every `[[model]]` gives every `[[constant]]`
//! and nothing else, names are unique (a constant is read by scale expressions, so it may not share
//! a parameter's name), constants and models cite their source, and there are models to give
//! declared constants.

use std::collections::BTreeSet;

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

/// Reports incomplete, unknown, repeated or uncited constants and models.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let declared: BTreeSet<&str> = device.constants.iter().map(|c| c.name.as_str()).collect();
    let mut seen = BTreeSet::new();
    for c in &device.constants {
        let error = |message: String| Diagnostic::error(RULE, c.span.clone(), message);
        if !seen.insert(c.name.as_str()) {
            out.push(error(format!("constant `{}` is declared twice", c.name)));
        }
        if device.parameter(&c.name).is_some() {
            out.push(error(format!(
                "constant `{}` has the name of a parameter: scale expressions could not tell them apart",
                c.name
            )));
        }
        if c.source.is_none() {
            out.push(error(format!("constant `{}` cites no source", c.name)));
        }
    }
    if device.models.is_empty() {
        if let Some(c) = device.constants.first() {
            out.push(
                Diagnostic::error(
                    RULE,
                    c.span.clone(),
                    "constants need `[[model]]`s to give them",
                )
                .help("add `[[model]]` with `constants = { name = value }`"),
            );
        }
    }
    let mut models = BTreeSet::new();
    for m in &device.models {
        let error = |message: String| Diagnostic::error(RULE, m.span.clone(), message);
        if !models.insert(m.name.as_str()) {
            out.push(error(format!("model `{}` is declared twice", m.name)));
        }
        if m.source.is_none() {
            out.push(error(format!("model `{}` cites no source", m.name)));
        }
        let given: BTreeSet<&str> = m.constants.iter().map(|(n, _)| n.as_str()).collect();
        for missing in declared.difference(&given) {
            out.push(error(format!(
                "model `{}` does not give constant `{missing}`",
                m.name
            )));
        }
        for unknown in given.difference(&declared) {
            out.push(
                Diagnostic::error(
                    RULE,
                    m.constants_span.clone(),
                    format!(
                        "model `{}` gives `{unknown}`, which is not a `[[constant]]`",
                        m.name
                    ),
                )
                .help("declare it with `[[constant]]` name = \"...\""),
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::{device, messages};

    const PEAK: &str = r#"
[[constant]]
name = "peak_current"
unit = "A"
source = { doc = "m", line = 227 }
"#;

    #[test]
    fn complete_models_check_clean() {
        let body = format!("{PEAK}[[model]]\nname = \"fd123\"\nconstants = {{ peak_current = 45 }}\nsource = {{ doc = \"m\", line = 227 }}\n");
        let d = device(&body);
        assert_eq!(
            d.models[0].value("peak_current").map(|r| r.numerator()),
            Some(45)
        );
    }

    #[test]
    fn a_missing_or_unknown_constant_is_reported() {
        let body = format!("{PEAK}[[model]]\nname = \"fd123\"\nconstants = {{ gear = \"1/2\" }}\nsource = {{ doc = \"m\", line = 227 }}\n");
        assert_eq!(
            messages(RULE, &body),
            [
                "model `fd123` does not give constant `peak_current`",
                "model `fd123` gives `gear`, which is not a `[[constant]]`"
            ]
        );
    }

    #[test]
    fn constants_without_models_are_reported() {
        assert_eq!(
            messages(RULE, PEAK),
            ["constants need `[[model]]`s to give them"]
        );
    }
}

//! A citation's `name`, the manual's own name of a register or object, becomes the generated
//! accessor's `#[doc(alias)]`: it must be text rustdoc accepts as an alias (no quotes, no tabs or
//! line breaks, no space at either end) and not the accessor's own name.

use crate::diagnostic::Diagnostic;
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

/// Why rustdoc would refuse `alias` on an item called `item`, if it would.
fn unfit_alias(alias: &str, item: &str) -> Option<&'static str> {
    if alias.trim().is_empty() {
        Some("is empty")
    } else if alias.starts_with(' ') || alias.ends_with(' ') {
        Some("starts or ends with a space")
    } else if alias
        .chars()
        .any(|c| c == '"' || c == '\'' || (c.is_whitespace() && c != ' '))
    {
        Some("holds a quote, a tab or a line break")
    } else if alias == item {
        Some("is the parameter's own name")
    } else {
        None
    }
}

/// Reports manual names the generated code could not carry as search aliases.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    device
        .parameters
        .iter()
        .filter_map(|p| {
            let citation = p.source.as_ref()?;
            let name = citation.name.as_deref()?;
            let why = unfit_alias(name, &p.name)?;
            Some(
                Diagnostic::error(
                    RULE,
                    citation.span.clone(),
                    format!("the manual name {name:?} of `{}` {why}", p.name),
                )
                .help("write the name as the manual prints it, on one line, without quotes"),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::unfit_alias;

    #[test]
    fn names_rustdoc_refuses_are_reported() {
        assert_eq!(unfit_alias("BUS DC LINK", "bus_dc_link"), None);
        assert_eq!(unfit_alias("Load (DH) / Status (DL)", "load"), None);
        assert!(unfit_alias(" C01", "x").is_some());
        assert!(unfit_alias("C\t01", "x").is_some());
        assert!(unfit_alias("say \"hi\"", "x").is_some());
        assert!(unfit_alias("", "x").is_some());
        assert!(unfit_alias("speed", "speed").is_some());
    }
}

//! The name of a member described over a sub-index run becomes a handle method (`drive.<name>(n)`),
//! a type in `indexed` and, with `_run`, the marker in `params`: none may be a parameter's or
//! another run's.

use std::collections::HashMap;

use crate::diagnostic::Diagnostic;
use crate::ir::Device;
use crate::names::{camel, method};

const RULE: &str = super::rule_name(module_path!());

/// Reports a run whose accessor name is already a parameter's or another run's.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut taken: HashMap<String, &str> = device
        .parameters
        .iter()
        .map(|p| (method(&p.name), p.name.as_str()))
        .collect();
    let mut types: HashMap<String, &str> = HashMap::new();
    let mut markers: HashMap<String, &str> = device
        .parameters
        .iter()
        .map(|p| (camel(&p.name), p.name.as_str()))
        .collect();
    let mut out = Vec::new();
    for run in &device.indexed {
        let clash = taken
            .insert(method(&run.name), &run.name)
            .or_else(|| types.insert(camel(&run.name), &run.name))
            .or_else(|| markers.insert(camel(&run.marker_name()), &run.name));
        if let Some(first) = clash {
            out.push(
                Diagnostic::error(
                    RULE,
                    run.span.clone(),
                    format!(
                        "the sub-index run `{}` has the accessor name of `{first}`",
                        run.name
                    ),
                )
                .help("rename the run or the parameter"),
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn a_run_named_like_a_parameter_is_refused() {
        let body = r#"
[[parameter]]
name = "limit"
type = "u8"
canopen = { index = 0x2000, access = "rw" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "limit"
type = "u32"
canopen = { index = 0x6693, subindex = "1..=2", access = "rw" }
source = { doc = "m", line = 2 }
"#;
        let found = messages(RULE, body);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(messages(
            RULE,
            &body.replace(
                "name = \"limit\"\ntype = \"u8\"",
                "name = \"other\"\ntype = \"u8\""
            )
        )
        .is_empty());
    }

    #[test]
    fn a_run_whose_marker_is_named_like_a_parameter_is_refused() {
        let body = r#"
[[parameter]]
name = "limit_run"
type = "u8"
canopen = { index = 0x2000, access = "rw" }
source = { doc = "m", line = 1 }

[[parameter]]
name = "limit"
type = "u32"
canopen = { index = 0x6693, subindex = "1..=2", access = "rw" }
source = { doc = "m", line = 2 }
"#;
        assert_eq!(messages(RULE, body).len(), 1);
    }
}

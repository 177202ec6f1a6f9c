//! No two items become the same Rust identifier: parameters, enums and flags types, enum values,
//! flag bits and fields — compared after sanitizing, so `Speed` and `speed` collide.

use std::collections::BTreeMap;

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::Device;
use crate::names as ident;

const RULE: &str = super::rule_name(module_path!());

fn duplicates<'a>(
    what: &str,
    items: impl IntoIterator<Item = (&'a str, String, &'a Span)>,
    out: &mut Vec<Diagnostic>,
) {
    let mut seen: BTreeMap<String, &str> = BTreeMap::new();
    for (name, ident, span) in items {
        match seen.get(&ident) {
            Some(first) => out.push(
                Diagnostic::error(
                    RULE,
                    span.clone(),
                    format!("{what} `{name}` has the same Rust name `{ident}` as `{first}`"),
                )
                .help("rename one of them"),
            ),
            None => {
                seen.insert(ident, name);
            }
        }
    }
}

/// Reports names that collide once turned into Rust identifiers.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    duplicates(
        "parameter",
        device
            .parameters
            .iter()
            .map(|p| (p.name.as_str(), ident::method(&p.name), &p.spans.name)),
        &mut out,
    );
    let types = device
        .enums
        .iter()
        .map(|e| (e.name.as_str(), ident::camel(&e.name), &e.span))
        .chain(
            device
                .flags
                .iter()
                .map(|f| (f.name.as_str(), ident::camel(&f.name), &f.span)),
        );
    duplicates("type", types, &mut out);
    duplicates(
        "variant",
        device
            .variants
            .iter()
            .map(|v| (v.name.as_str(), ident::camel(&v.name), &v.span)),
        &mut out,
    );
    for e in &device.enums {
        duplicates(
            "enum value",
            e.values
                .iter()
                .map(|v| (v.name.as_str(), ident::constant(&v.name), &v.span)),
            &mut out,
        );
    }
    for f in &device.flags {
        let bits = f
            .bits
            .iter()
            .map(|b| (b.name.as_str(), ident::constant(&b.name), &b.span));
        let fields = f
            .fields
            .iter()
            .map(|x| (x.name.as_str(), ident::constant(&x.name), &x.span));
        duplicates("bit or field", bits.chain(fields), &mut out);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn names_colliding_after_case_conversion_are_reported() {
        let body = r#"
[[parameter]]
name = "Speed"
type = "u16"
modbus = { table = "holding", address = 1 }
source = { doc = "m", line = 1 }
[[parameter]]
name = "speed"
type = "u16"
modbus = { table = "holding", address = 2 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["parameter `speed` has the same Rust name `speed` as `Speed`"]
        );
    }
}

//! Every `enum`, `flags`, `record`, `variant` and field enum a description names is declared.

use crate::diagnostic::{Diagnostic, Span};
use crate::ir::Device;

const RULE: &str = super::rule_name(module_path!());

fn missing(kind: &str, name: &str, span: Span, known: Vec<&str>) -> Diagnostic {
    let help = if known.is_empty() {
        format!("no {kind} is declared; add a [[{kind}]] table")
    } else {
        format!("declared: {}", known.join(", "))
    };
    Diagnostic::error(RULE, span, format!("{kind} `{name}` is not declared")).help(help)
}

/// Reports references to undeclared enums, flags, records and variants.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let enums: Vec<&str> = device.enums.iter().map(|e| e.name.as_str()).collect();
    let flags: Vec<&str> = device.flags.iter().map(|f| f.name.as_str()).collect();
    let records: Vec<&str> = device.records.iter().map(|r| r.name.as_str()).collect();
    let variants: Vec<&str> = device.variants.iter().map(|v| v.name.as_str()).collect();
    let mut out = Vec::new();
    let mut need = |kind: &str, known: &[&str], name: &str, span: &Span| {
        if !known.contains(&name) {
            out.push(missing(kind, name, span.clone(), known.to_vec()));
        }
    };
    for p in &device.parameters {
        let s = &p.spans;
        if let (Some(e), Some(span)) = (&p.enumeration, &s.enumeration) {
            need("enum", &enums, e, span);
        }
        if let (Some(f), Some(span)) = (&p.flags, &s.flags) {
            need("flags", &flags, f, span);
        }
        if let (Some(r), Some(span)) = (&p.record, &s.record) {
            need("record", &records, r, span);
        }
        for (v, span) in p.variants.iter().zip(&s.variants) {
            need("variant", &variants, v, span);
        }
        let address_variants = p.modbus.iter().map(|a| (&a.variant, &a.span));
        let object_variants = p
            .canopen
            .iter()
            .chain(&p.rs232)
            .map(|a| (&a.variant, &a.span));
        for (v, span) in address_variants.chain(object_variants) {
            if let Some(v) = v {
                need("variant", &variants, v, span);
            }
        }
    }
    for f in &device.flags {
        for field in &f.fields {
            if let Some(e) = &field.enumeration {
                need("enum", &enums, e, &field.span);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    #[test]
    fn undeclared_enum_is_reported() {
        let body = r#"
[[parameter]]
name = "mode"
type = "u8"
enum = "modes"
modbus = { table = "holding", address = 1 }
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["enum `modes` is not declared"]
        );
    }

    #[test]
    fn undeclared_variant_on_an_address_is_reported() {
        let body = r#"
[[variant]]
name = "pc400"
[[parameter]]
name = "x"
type = "u16"
modbus = [{ table = "holding", address = 1, variant = "pc500" }]
source = { doc = "m", line = 1 }
"#;
        assert_eq!(
            messages(RULE, body),
            ["variant `pc500` is not declared"]
        );
    }
}

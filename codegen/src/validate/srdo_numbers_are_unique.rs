//! Two declared SRDOs never share a number (one communication object each) or a generated name.

use std::collections::HashMap;

use crate::diagnostic::Diagnostic;
use crate::ir::Device;
use crate::names::camel;

const RULE: &str = "srdo_numbers_are_unique";

/// Reports a repeated number and a repeated struct name.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut numbers: HashMap<u8, &str> = HashMap::new();
    let mut names: HashMap<String, &str> = HashMap::new();
    let mut out = Vec::new();
    for s in &device.srdos {
        if let Some(first) = numbers.insert(s.number, &s.name) {
            out.push(
                Diagnostic::error(
                    RULE,
                    s.span.clone(),
                    format!("SRDO `{}` has the number of `{first}`", s.name),
                )
                .help("SRDO n has communication object 1300h + n; each number once"),
            );
        }
        if let Some(first) = names.insert(camel(&s.name), &s.name) {
            out.push(
                Diagnostic::error(
                    RULE,
                    s.span.clone(),
                    format!("SRDO `{}` has the same generated name as `{first}`", s.name),
                )
                .help("rename one of them"),
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use crate::validate::test_support::messages;

    fn srdo(name: &str, number: u8) -> String {
        format!("[[srdo]]\nname = \"{name}\"\nnumber = {number}\ndirection = \"rx\"\nsct_ms = 50\nsrvt_ms = 20\ncob_ids = [0x101, 0x102]\nentries = [\"w\", \"w\"]\n")
    }

    const WORD: &str = "[[parameter]]\nname = \"w\"\ntype = \"u8\"\ncanopen = { index = 0x6620, subindex = 1 }\nsource = { doc = \"m\", line = 1 }\n";

    #[test]
    fn repeated_numbers_and_names_are_reported() {
        let body = format!("{WORD}{}{}{}", srdo("a", 1), srdo("b", 1), srdo("A", 2));
        assert_eq!(
            messages("srdo_numbers_are_unique", &body),
            [
                "SRDO `b` has the number of `a`",
                "SRDO `A` has the same generated name as `a`",
            ]
        );
    }
}

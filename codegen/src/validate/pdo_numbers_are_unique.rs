//! Two declared PDOs of one direction never share a number, and no two share a name (the name
//! becomes the generated struct).

use std::collections::HashMap;

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, PdoDirection};
use crate::names::camel;

const RULE: &str = "pdo_numbers_are_unique";

/// Reports a repeated `(direction, number)` and a repeated struct name.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut numbers: HashMap<(PdoDirection, u16), &str> = HashMap::new();
    let mut names: HashMap<String, &str> = HashMap::new();
    let mut out = Vec::new();
    for m in &device.pdos {
        if let Some(first) = numbers.insert((m.direction, m.number), &m.name) {
            out.push(
                Diagnostic::error(RULE, m.span.clone(), format!("PDO `{}` has the number of `{first}`", m.name))
                    .help("each direction numbers its PDOs once (communication object 0x1400/0x1800 + number − 1)"),
            );
        }
        if let Some(first) = names.insert(camel(&m.name), &m.name) {
            out.push(
                Diagnostic::error(
                    RULE,
                    m.span.clone(),
                    format!("PDO `{}` has the same generated name as `{first}`", m.name),
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

    fn pdo(name: &str, direction: &str, number: u16) -> String {
        format!("[[pdo]]\nname = \"{name}\"\ndirection = \"{direction}\"\nnumber = {number}\ncob_id = 0x181\nentries = [\"s\"]\nsource = {{ doc = \"m\", line = 3 }}\n")
    }

    const STATUS: &str = "[[parameter]]\nname = \"s\"\ntype = \"u16\"\ncanopen = { index = 0x6041, pdo = \"both\" }\nsource = { doc = \"m\", line = 1 }\n";

    #[test]
    fn one_number_per_direction_is_fine() {
        let body = format!("{STATUS}{}{}", pdo("tpdo1", "tx", 1), pdo("rpdo1", "rx", 1));
        assert!(messages("pdo_numbers_are_unique", &body).is_empty());
    }

    #[test]
    fn repeated_numbers_and_names_are_reported() {
        let body = format!(
            "{STATUS}{}{}{}",
            pdo("a", "tx", 1),
            pdo("b", "tx", 1),
            pdo("A", "rx", 2)
        );
        assert_eq!(
            messages("pdo_numbers_are_unique", &body),
            [
                "PDO `b` has the number of `a`",
                "PDO `A` has the same generated name as `a`",
            ]
        );
    }
}

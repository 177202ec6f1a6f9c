//! Two declared mappings never share a communication object (a PDO number per direction, an SRDO
//! number), and no two of one kind share a name (the name becomes the generated struct in the
//! kind's module).

use std::collections::HashMap;

use crate::diagnostic::Diagnostic;
use crate::ir::{Device, Mapping, MappingKind};
use crate::names::camel;

const RULE: &str = super::rule_name(module_path!());

/// Reports a repeated communication object and a repeated struct name.
pub fn check(device: &Device) -> Vec<Diagnostic> {
    let mut objects: HashMap<u16, &str> = HashMap::new();
    let mut names: HashMap<(&str, String), &str> = HashMap::new();
    let mut out = Vec::new();
    for m in &device.mappings {
        let (label, error) = (m.label(), |message| {
            Diagnostic::error(RULE, m.span.clone(), message)
        });
        let communication = m.object_indices().map(|(communication, _)| communication);
        if let Some(first) = communication.and_then(|index| objects.insert(index, &m.name)) {
            let message = format!("{label} `{}` has the number of `{first}`", m.name);
            out.push(error(message).help(numbering(m)));
        }
        if let Some(first) = names.insert((label, camel(&m.name)), &m.name) {
            let message = format!(
                "{label} `{}` has the same generated name as `{first}`",
                m.name
            );
            out.push(error(message).help("rename one of them"));
        }
    }
    out
}

/// How the kind numbers its communication objects.
fn numbering(m: &Mapping) -> &'static str {
    match m.kind {
        MappingKind::Pdo(_) => {
            "each direction numbers its PDOs once (communication object 0x1400/0x1800 + number − 1)"
        }
        MappingKind::Srdo(_) => "SRDO n has communication object 1300h + n; each number once",
    }
}

#[cfg(test)]
mod tests {
    use super::RULE;
    use crate::validate::test_support::messages;

    fn pdo(name: &str, direction: &str, number: u16) -> String {
        format!("[[pdo]]\nname = \"{name}\"\ndirection = \"{direction}\"\nnumber = {number}\ncob_id = 0x181\nentries = [\"s\"]\nsource = {{ doc = \"m\", line = 3 }}\n")
    }

    fn srdo(name: &str, number: u8) -> String {
        format!("[[srdo]]\nname = \"{name}\"\nnumber = {number}\ndirection = \"rx\"\nsct_ms = 50\nsrvt_ms = 20\ncob_ids = [0x101, 0x102]\nentries = [\"w\", \"w\"]\n")
    }

    const STATUS: &str = "[[parameter]]\nname = \"s\"\ntype = \"u16\"\ncanopen = { index = 0x6041, pdo = \"both\" }\nsource = { doc = \"m\", line = 1 }\n";

    const WORD: &str = "[[parameter]]\nname = \"w\"\ntype = \"u8\"\ncanopen = { index = 0x6620, subindex = 1 }\nsource = { doc = \"m\", line = 1 }\n";

    #[test]
    fn one_number_per_direction_and_kind_is_fine() {
        let body = format!(
            "{STATUS}{WORD}{}{}{}",
            pdo("tpdo1", "tx", 1),
            pdo("rpdo1", "rx", 1),
            srdo("tpdo1", 1)
        );
        assert!(messages(RULE, &body).is_empty());
    }

    #[test]
    fn repeated_pdo_numbers_and_names_are_reported() {
        let body = format!(
            "{STATUS}{}{}{}",
            pdo("a", "tx", 1),
            pdo("b", "tx", 1),
            pdo("A", "rx", 2)
        );
        assert_eq!(
            messages(RULE, &body),
            [
                "PDO `b` has the number of `a`",
                "PDO `A` has the same generated name as `a`",
            ]
        );
    }

    #[test]
    fn repeated_srdo_numbers_and_names_are_reported() {
        let body = format!("{WORD}{}{}{}", srdo("a", 1), srdo("b", 1), srdo("A", 2));
        assert_eq!(
            messages(RULE, &body),
            [
                "SRDO `b` has the number of `a`",
                "SRDO `A` has the same generated name as `a`",
            ]
        );
    }
}

//! Rust identifiers from description names: sanitized, never able to inject code.
//!
//! Any character outside `[A-Za-z0-9_]` becomes `_`, a leading digit gets a prefix, and keywords
//! get a trailing `_`. Distinct names that sanitize to the same identifier are caught by the
//! `names_are_unique` validation pass, which uses these same functions.

use heck::{ToSnakeCase, ToUpperCamelCase};

const KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern",
    "false", "fn", "for", "gen", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut",
    "pub", "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "type",
    "unsafe", "use", "where", "while", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "try", "typeof", "unsized", "virtual", "yield", "union",
];

/// Method names the generated drive handle defines itself; parameters get a `_` suffix instead.
const HANDLE_METHODS: &[&str] = &[
    "new",
    "modbus",
    "canopen",
    "device",
    "into_link",
    "link_mut",
    "read_many",
    "variant",
    "set_variant",
];

fn ascii_words(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

fn finish(ident: String, digit_prefix: &str, fallback: &str) -> String {
    let ident = if ident.is_empty() {
        fallback.to_owned()
    } else {
        ident
    };
    let ident = if ident.starts_with(|c: char| c.is_ascii_digit()) {
        format!("{digit_prefix}{ident}")
    } else {
        ident
    };
    if KEYWORDS.contains(&ident.as_str()) {
        format!("{ident}_")
    } else {
        ident
    }
}

/// A `snake_case` identifier (modules, methods, fields).
pub fn snake(name: &str) -> String {
    finish(snake_words(name), "_", "unnamed")
}

/// An `UpperCamelCase` identifier (types, enum values, flag constants use [`constant`]).
pub fn camel(name: &str) -> String {
    finish(camel_words(name), "V", "Unnamed")
}

/// Whether `name` is snake case already: words of lowercase ASCII letters and digits joined by
/// single underscores, as most description names are. heck leaves such a name as it is and
/// capitalizes each of its words; its general path formats character by character, which was a
/// third of loading a description (issue 33: `drivegen trace` loads one before its first frame).
fn is_plain_snake(name: &str) -> bool {
    name.split('_').all(|word| {
        !word.is_empty()
            && word
                .bytes()
                .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit())
    })
}

/// `name`'s words in snake case, as heck writes them.
fn snake_words(name: &str) -> String {
    if is_plain_snake(name) {
        return name.to_owned();
    }
    ascii_words(name).to_snake_case()
}

/// `name`'s words in upper camel case, as heck writes them.
fn camel_words(name: &str) -> String {
    if !is_plain_snake(name) {
        return ascii_words(name).to_upper_camel_case();
    }
    let mut out = String::with_capacity(name.len());
    for word in name.split('_') {
        // A plain word is ASCII and not empty: its first byte is a whole character.
        let (first, rest) = word.split_at(1);
        out.extend(first.chars().map(|c| c.to_ascii_uppercase()));
        out.push_str(rest);
    }
    out
}

/// A `SCREAMING_SNAKE_CASE` identifier (associated constants).
pub fn constant(name: &str) -> String {
    finish(
        snake(name).trim_end_matches('_').to_uppercase(),
        "V",
        "UNNAMED",
    )
}

/// The accessor method name of a parameter on the drive handle.
pub fn method(name: &str) -> String {
    let ident = snake(name);
    if HANDLE_METHODS.contains(&ident.as_str()) {
        format!("{ident}_")
    } else {
        ident
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hostile_names_become_plain_identifiers() {
        assert_eq!(snake("type"), "type_");
        assert_eq!(snake("1st speed"), "_1st_speed");
        assert_eq!(camel("9600"), "V9600");
        assert_eq!(snake("températüre"), "temp_rat_re");
        assert_eq!(snake("x\"); drop(\"y"), "x_drop_y");
        assert_eq!(camel("Self"), "Self_");
        assert_eq!(constant("run velocity"), "RUN_VELOCITY");
        assert_eq!(constant("self"), "SELF");
        assert_eq!(snake(""), "unnamed");
        assert_eq!(method("read_many"), "read_many_");
    }

    /// The shortcut for names in snake case gives what heck gives, over names of the bytes
    /// that matter to either (letters of both cases, digits, underscores, other characters).
    #[test]
    fn plain_snake_names_are_cased_as_heck_cases_them() {
        const BYTES: &[u8] = b"abz09AZ__ -";
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut plain = 0;
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let len = (state % 9) as usize;
            let name: String = (0..len)
                .map(|i| char::from(BYTES[(state >> (6 * i + 4)) as usize % BYTES.len()]))
                .collect();
            plain += usize::from(is_plain_snake(&name));
            let words = ascii_words(&name);
            assert_eq!(snake_words(&name), words.to_snake_case(), "{name:?}");
            assert_eq!(camel_words(&name), words.to_upper_camel_case(), "{name:?}");
        }
        assert!(plain > 1000, "{plain}");
    }

    #[test]
    fn every_output_parses_as_an_identifier() {
        for name in [
            "",
            "*/",
            "}",
            "a-b",
            "ü",
            "9",
            "crate",
            "r#x",
            "__",
            "fn main(){}",
        ] {
            for ident in [snake(name), camel(name), constant(name), method(name)] {
                assert!(
                    syn::parse_str::<syn::Ident>(&ident).is_ok(),
                    "{name:?} -> {ident:?}"
                );
            }
        }
    }
}

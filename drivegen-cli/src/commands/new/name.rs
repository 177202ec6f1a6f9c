//! The crate name `drivegen new` accepts: what Cargo and crates.io accept, checked before anything
//! is written.

use std::fmt;

/// Longest name crates.io accepts.
const MAX_LEN: usize = 64;

/// Names Cargo refuses or that would shadow a standard crate.
const RESERVED: &[&str] = &[
    "alloc",
    "core",
    "proc_macro",
    "proc-macro",
    "std",
    "test",
    "build",
    "deps",
    "examples",
];

/// Rust keywords: the crate's library name may not be one.
const KEYWORDS: &[&str] = &[
    "abstract", "as", "async", "await", "become", "box", "break", "const", "continue", "crate",
    "do", "dyn", "else", "enum", "extern", "false", "final", "fn", "for", "gen", "if", "impl",
    "in", "let", "loop", "macro", "match", "mod", "move", "mut", "override", "priv", "pub", "ref",
    "return", "self", "Self", "static", "struct", "super", "trait", "true", "try", "type",
    "typeof", "unsafe", "unsized", "use", "virtual", "where", "while", "yield",
];

/// Why a crate name was refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum InvalidName {
    /// The name is empty.
    Empty,
    /// Longer than crates.io accepts.
    TooLong(usize),
    /// A character other than an ASCII letter, digit, `-` or `_`.
    Character(char),
    /// The name does not start with an ASCII letter.
    Start(char),
    /// A Rust keyword or a name Cargo reserves.
    Reserved,
}

impl fmt::Display for InvalidName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty => write!(f, "the name is empty"),
            Self::TooLong(len) => write!(f, "{len} characters, crates.io takes at most {MAX_LEN}"),
            Self::Character(c) => write!(
                f,
                "`{c}` is not allowed: use ASCII letters, digits, `-` and `_`"
            ),
            Self::Start(c) => write!(f, "it starts with `{c}`: start with an ASCII letter"),
            Self::Reserved => write!(f, "it is a Rust keyword or a name Cargo reserves"),
        }
    }
}

/// Checks `name` as a crate name (`my-drive`, `acme_fd3`).
pub fn check(name: &str) -> Result<(), InvalidName> {
    let first = name.chars().next().ok_or(InvalidName::Empty)?;
    if name.len() > MAX_LEN {
        return Err(InvalidName::TooLong(name.len()));
    }
    if let Some(c) = name
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || *c == '-' || *c == '_'))
    {
        return Err(InvalidName::Character(c));
    }
    if !first.is_ascii_alphabetic() {
        return Err(InvalidName::Start(first));
    }
    let library = name.replace('-', "_");
    if RESERVED.contains(&name) || KEYWORDS.contains(&library.as_str()) {
        return Err(InvalidName::Reserved);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepts_the_names_cargo_accepts() {
        for name in ["my-drive", "acme_fd3", "x", "Lafert-Smartris2"] {
            assert_eq!(check(name), Ok(()), "{name}");
        }
    }

    #[test]
    fn refuses_each_kind_of_bad_name() {
        assert_eq!(check(""), Err(InvalidName::Empty));
        assert_eq!(check("my drive"), Err(InvalidName::Character(' ')));
        assert_eq!(check("drive.rs"), Err(InvalidName::Character('.')));
        assert_eq!(check("3phase"), Err(InvalidName::Start('3')));
        assert_eq!(check("-drive"), Err(InvalidName::Start('-')));
        assert_eq!(check("fn"), Err(InvalidName::Reserved));
        assert_eq!(check("std"), Err(InvalidName::Reserved));
        assert_eq!(check(&"a".repeat(65)), Err(InvalidName::TooLong(65)));
    }
}

//! What DBC text may hold: C identifiers for names, strings without double quotes, numbers in
//! the shortest form that reads back the same.

/// `name` as a DBC identifier: letters, digits and `_`, not starting with a digit.
pub fn identifier(name: &str) -> String {
    let mut out: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if out.is_empty() || out.starts_with(|c: char| c.is_ascii_digit()) {
        out.insert(0, '_');
    }
    out
}

/// `text` inside a DBC string: a DBC string has no escape, so a double quote becomes a single
/// one, and line breaks become spaces.
pub fn string(text: &str) -> String {
    text.replace('"', "'").replace(['\n', '\r'], " ")
}

/// A number as DBC writes it: `0.1`, `-5`, `4294967295`.
pub fn number(value: f64) -> String {
    if value == value.trunc() && value.abs() < 1e18 {
        format!("{}", value as i64)
    } else {
        format!("{value}")
    }
}

//! What the TOML files drivegen reads for its commands (configuration backups, network files)
//! share: reading with serde into the file's raw shape, its `format` version checked, and the
//! line of a byte offset for messages.

use std::collections::BTreeMap;

use serde::de::DeserializeOwned;
use toml::Spanned;

/// Why a file could not be read at all, with the line when there is one.
pub(crate) enum Unreadable {
    /// Not TOML, an unknown key, a value of the wrong type: the message.
    Syntax(Option<u32>, String),
    /// No `format`.
    MissingFormat,
    /// Another `format` than the one read: its line and value.
    UnsupportedFormat(u32, i64),
}

/// `text` read into `T`, whose `format` (given by `format_of`) must be `version`.
pub(crate) fn read<T: DeserializeOwned>(
    text: &str,
    version: u32,
    format_of: impl FnOnce(&T) -> Option<&Spanned<i64>>,
) -> Result<T, Unreadable> {
    let raw: T = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|span| line_of(text, span.start));
        Unreadable::Syntax(line, e.message().to_owned())
    })?;
    let format = format_of(&raw).ok_or(Unreadable::MissingFormat)?;
    if *format.get_ref() != i64::from(version) {
        return Err(Unreadable::UnsupportedFormat(
            line_of(text, format.span().start),
            *format.get_ref(),
        ));
    }
    Ok(raw)
}

/// The 1-based line of byte `offset` of `text`.
pub(crate) fn line_of(text: &str, offset: usize) -> u32 {
    let end = offset.min(text.len());
    let before = text.get(..end).unwrap_or(text);
    u32::try_from(before.matches('\n').count() + 1).unwrap_or(u32::MAX)
}

/// The entries of a table in the order of the file, each with its key's line.
pub(crate) fn in_file_order(
    text: &str,
    table: BTreeMap<Spanned<String>, toml::Value>,
) -> impl Iterator<Item = (String, u32, toml::Value)> + '_ {
    let mut entries: Vec<_> = table
        .into_iter()
        .map(|(key, value)| (key.span().start, key.into_inner(), value))
        .collect();
    entries.sort_by_key(|(start, _, _)| *start);
    entries
        .into_iter()
        .map(move |(start, name, value)| (name, line_of(text, start), value))
}

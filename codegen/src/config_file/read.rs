//! Text to [`ConfigFile`]: TOML through serde, then each entry checked for its shape, with the
//! line it is on.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use super::error::{ConfigFileError, ConfigFileErrorKind as Kind};
use super::{
    ConfigFile, DescriptionRef, DriveRecord, IdentityEntry, SavedParameter, SavedRaw, Unread,
    FORMAT_VERSION,
};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    format: Option<Spanned<i64>>,
    description: Option<RawDescription>,
    drive: Option<RawDrive>,
    #[serde(default)]
    identity: BTreeMap<Spanned<String>, toml::Value>,
    #[serde(default)]
    parameters: BTreeMap<Spanned<String>, toml::Value>,
    #[serde(default)]
    unread: BTreeMap<Spanned<String>, toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDescription {
    name: String,
    firmware: Option<String>,
    path: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDrive {
    target: String,
    variant: Option<String>,
    pulled_at: String,
}

/// Reads a configuration file. Every entry keeps its line; a file that is not TOML, cut short,
/// of another format version or with an entry of the wrong shape is refused with the line.
pub fn parse(text: &str) -> Result<ConfigFile, ConfigFileError> {
    let raw: RawFile = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|span| line_of(text, span.start));
        ConfigFileError::at(line, Kind::Syntax(e.message().to_owned()))
    })?;
    let format = raw
        .format
        .ok_or(ConfigFileError::at(None, Kind::Missing("format")))?;
    if *format.get_ref() != i64::from(FORMAT_VERSION) {
        return Err(ConfigFileError::at(
            Some(line_of(text, format.span().start)),
            Kind::UnsupportedFormat(*format.get_ref()),
        ));
    }
    let description = raw
        .description
        .ok_or(ConfigFileError::at(None, Kind::Missing("[description]")))?;
    let drive = raw
        .drive
        .ok_or(ConfigFileError::at(None, Kind::Missing("[drive]")))?;
    let identity = sorted(text, raw.identity)
        .map(|(name, line, value)| {
            let raw = int_of(&value).ok_or_else(|| malformed(line, &name, "an integer"))?;
            Ok(IdentityEntry { name, raw, line })
        })
        .collect::<Result<_, ConfigFileError>>()?;
    let parameters: Vec<SavedParameter> = sorted(text, raw.parameters)
        .map(|(name, line, value)| saved(name, line, &value))
        .collect::<Result<_, _>>()?;
    let unread: Vec<Unread> = sorted(text, raw.unread)
        .map(|(name, line, value)| match value {
            toml::Value::String(reason) => Ok(Unread { name, reason, line }),
            _ => Err(malformed(line, &name, "the reason as a string")),
        })
        .collect::<Result<_, _>>()?;
    if let Some(both) = unread
        .iter()
        .find(|u| parameters.iter().any(|p| p.name == u.name))
    {
        return Err(ConfigFileError::at(
            Some(both.line),
            Kind::Duplicate(both.name.clone()),
        ));
    }
    Ok(ConfigFile {
        description: DescriptionRef {
            name: description.name,
            firmware: description.firmware,
            path: description.path,
        },
        drive: DriveRecord {
            target: drive.target,
            variant: drive.variant,
            pulled_at: drive.pulled_at,
        },
        identity,
        parameters,
        unread,
    })
}

/// The entries of a table in the order of the file, each with its key's line.
fn sorted(
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

/// One `name = { value = "...", raw = ..., unit = "..." }` entry.
fn saved(name: String, line: u32, value: &toml::Value) -> Result<SavedParameter, ConfigFileError> {
    const SHAPE: &str = "{ value = \"...\", raw = ... } with an optional unit";
    let table = value
        .as_table()
        .ok_or_else(|| malformed(line, &name, SHAPE))?;
    if table
        .keys()
        .any(|k| !matches!(k.as_str(), "value" | "raw" | "unit"))
    {
        return Err(malformed(line, &name, SHAPE));
    }
    let text = table
        .get("value")
        .and_then(toml::Value::as_str)
        .ok_or_else(|| malformed(line, &name, "a `value` string"))?;
    let raw = table
        .get("raw")
        .and_then(raw_of)
        .ok_or_else(|| malformed(line, &name, "a `raw` integer, float or byte array"))?;
    let unit = match table.get("unit") {
        None => None,
        Some(toml::Value::String(unit)) => Some(unit.clone()),
        Some(_) => return Err(malformed(line, &name, "a `unit` string")),
    };
    Ok(SavedParameter {
        name,
        value: text.to_owned(),
        raw,
        unit,
        line,
    })
}

fn raw_of(value: &toml::Value) -> Option<SavedRaw> {
    match value {
        toml::Value::Float(float) => Some(SavedRaw::Float(*float)),
        toml::Value::Array(items) => items
            .iter()
            .map(|item| u8::try_from(item.as_integer()?).ok())
            .collect::<Option<Vec<u8>>>()
            .map(SavedRaw::Bytes),
        other => int_of(other).map(SavedRaw::Int),
    }
}

/// An integer, or one beyond 64 bits written as a decimal string.
fn int_of(value: &toml::Value) -> Option<i128> {
    match value {
        toml::Value::Integer(int) => Some(i128::from(*int)),
        toml::Value::String(text) => text.parse().ok(),
        _ => None,
    }
}

fn malformed(line: u32, key: &str, expected: &'static str) -> ConfigFileError {
    ConfigFileError::at(
        Some(line),
        Kind::Malformed {
            key: key.to_owned(),
            expected,
        },
    )
}

/// The 1-based line of byte `offset` of `text`.
fn line_of(text: &str, offset: usize) -> u32 {
    let end = offset.min(text.len());
    let before = text.get(..end).unwrap_or(text);
    u32::try_from(before.matches('\n').count() + 1).unwrap_or(u32::MAX)
}

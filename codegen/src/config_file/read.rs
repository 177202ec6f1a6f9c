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
use crate::toml_file::{self, in_file_order};

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
    let raw: RawFile = toml_file::read(text, FORMAT_VERSION, |raw: &RawFile| raw.format.as_ref())
        .map_err(ConfigFileError::unreadable)?;
    let description = raw
        .description
        .ok_or(ConfigFileError::at(None, Kind::Missing("[description]")))?;
    let drive = raw
        .drive
        .ok_or(ConfigFileError::at(None, Kind::Missing("[drive]")))?;
    let identity = in_file_order(text, raw.identity)
        .map(|(name, line, value)| {
            let raw = int_of(&value).ok_or_else(|| malformed(line, &name, "an integer"))?;
            Ok(IdentityEntry { name, raw, line })
        })
        .collect::<Result<_, ConfigFileError>>()?;
    let parameters: Vec<SavedParameter> = in_file_order(text, raw.parameters)
        .map(|(name, line, value)| saved(name, line, &value))
        .collect::<Result<_, _>>()?;
    let unread: Vec<Unread> = in_file_order(text, raw.unread)
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

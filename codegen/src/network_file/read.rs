//! Text to [`NetworkFile`]: TOML through serde, then each node checked for its shape, with the
//! line it is on.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use super::error::{NetworkFileError, NetworkFileErrorKind as Kind};
use super::{BootParameter, ExpectedIdentity, NetworkFile, NodeEntry, FORMAT_VERSION};
use crate::toml_file::{self, in_file_order, line_of, Unreadable};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    format: Option<Spanned<i64>>,
    #[serde(default)]
    node: Vec<Spanned<RawNode>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawNode {
    id: Spanned<i64>,
    description: String,
    identity: Option<Spanned<RawIdentity>>,
    heartbeat_ms: Option<Spanned<i64>>,
    start: Option<bool>,
    #[serde(default)]
    parameters: BTreeMap<Spanned<String>, toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawIdentity {
    vendor_id: Option<i64>,
    product_code: Option<i64>,
    revision: Option<i64>,
}

/// Reads a network file. A file that is not TOML, of another format, without nodes, with a
/// node id outside 1-127 or twice, or with an entry of the wrong shape is refused with the line.
pub fn parse(text: &str) -> Result<NetworkFile, NetworkFileError> {
    let raw: RawFile = toml_file::read(text, FORMAT_VERSION, |raw: &RawFile| raw.format.as_ref())
        .map_err(|unreadable| match unreadable {
        Unreadable::Syntax(line, why) => NetworkFileError::at(line, Kind::Syntax(why)),
        Unreadable::MissingFormat => NetworkFileError::at(None, Kind::MissingFormat),
        Unreadable::UnsupportedFormat(line, found) => {
            NetworkFileError::at(Some(line), Kind::UnsupportedFormat(found))
        }
    })?;
    if raw.node.is_empty() {
        return Err(NetworkFileError::at(None, Kind::NoNodes));
    }
    let mut nodes: Vec<NodeEntry> = Vec::new();
    for spanned in raw.node {
        let line = line_of(text, spanned.span().start);
        let node = node(text, line, spanned.into_inner())?;
        if nodes.iter().any(|n| n.id == node.id) {
            return Err(NetworkFileError::at(
                Some(line),
                Kind::DuplicateNode(node.id),
            ));
        }
        nodes.push(node);
    }
    Ok(NetworkFile { nodes })
}

fn node(text: &str, line: u32, raw: RawNode) -> Result<NodeEntry, NetworkFileError> {
    let id = u8::try_from(*raw.id.get_ref())
        .ok()
        .filter(|id| (1..=127).contains(id))
        .ok_or_else(|| {
            NetworkFileError::at(
                Some(line_of(text, raw.id.span().start)),
                Kind::NodeIdOutOfRange(*raw.id.get_ref()),
            )
        })?;
    let heartbeat_ms = raw
        .heartbeat_ms
        .map(|ms| {
            u16::try_from(*ms.get_ref()).map_err(|_| {
                malformed(line_of(text, ms.span().start), "heartbeat_ms", "0-65535 ms")
            })
        })
        .transpose()?;
    let identity = match raw.identity {
        None => ExpectedIdentity::default(),
        Some(spanned) => identity(line_of(text, spanned.span().start), spanned.get_ref())?,
    };
    Ok(NodeEntry {
        id,
        description: raw.description,
        identity,
        heartbeat_ms,
        start: raw.start.unwrap_or(true),
        parameters: parameters(text, raw.parameters)?,
        line,
    })
}

fn identity(line: u32, raw: &RawIdentity) -> Result<ExpectedIdentity, NetworkFileError> {
    let entry = |value: Option<i64>, key: &'static str| {
        value
            .map(|v| u32::try_from(v).map_err(|_| malformed(line, key, "a 32-bit unsigned value")))
            .transpose()
    };
    Ok(ExpectedIdentity {
        vendor_id: entry(raw.vendor_id, "vendor_id")?,
        product_code: entry(raw.product_code, "product_code")?,
        revision: entry(raw.revision, "revision")?,
    })
}

/// The boot parameters in the order of the file.
fn parameters(
    text: &str,
    table: BTreeMap<Spanned<String>, toml::Value>,
) -> Result<Vec<BootParameter>, NetworkFileError> {
    in_file_order(text, table)
        .map(|(name, line, value)| {
            let value = match value {
                toml::Value::String(text) => text,
                toml::Value::Integer(int) => int.to_string(),
                toml::Value::Float(float) => float.to_string(),
                toml::Value::Boolean(flag) => u8::from(flag).to_string(),
                _ => {
                    return Err(malformed(
                        line,
                        &name,
                        "a value as `drivegen write` takes it",
                    ))
                }
            };
            Ok(BootParameter { name, value, line })
        })
        .collect()
}

fn malformed(line: u32, key: &str, expected: &'static str) -> NetworkFileError {
    NetworkFileError::at(
        Some(line),
        Kind::Malformed {
            key: key.to_owned(),
            expected,
        },
    )
}

//! Text to [`NetworkFile`]: TOML through serde, then each node checked for its shape, with the
//! line it is on.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use super::error::{NetworkFileError, NetworkFileErrorKind as Kind};
use super::{
    BootParameter, ExpectedIdentity, MappedName, NetworkFile, NodeEntry, PdoEntry, FORMAT_VERSION,
};
use crate::ir::Direction;
use crate::toml_file::{self, in_file_order, line_of};

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
    tpdo: Vec<Spanned<RawPdo>>,
    #[serde(default)]
    rpdo: Vec<Spanned<RawPdo>>,
    #[serde(default)]
    parameters: BTreeMap<Spanned<String>, toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPdo {
    number: Spanned<i64>,
    cob_id: Option<Spanned<i64>>,
    transmission_type: Option<Spanned<i64>>,
    inhibit_time: Option<Spanned<i64>>,
    event_timer: Option<Spanned<i64>>,
    mapping: Vec<Spanned<String>>,
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
        .map_err(NetworkFileError::unreadable)?;
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
    let tpdos = raw.tpdo.into_iter().map(|p| (Direction::Tx, p));
    let rpdos = raw.rpdo.into_iter().map(|p| (Direction::Rx, p));
    let pdos = tpdos
        .chain(rpdos)
        .map(|(direction, spanned)| pdo(text, direction, spanned))
        .collect::<Result<_, _>>()?;
    Ok(NodeEntry {
        id,
        description: raw.description,
        identity,
        heartbeat_ms,
        start: raw.start.unwrap_or(true),
        pdos,
        parameters: parameters(text, raw.parameters)?,
        line,
    })
}

/// One PDO table, each number in its range (the description's checks come later).
fn pdo(
    text: &str,
    direction: Direction,
    spanned: Spanned<RawPdo>,
) -> Result<PdoEntry, NetworkFileError> {
    let line = line_of(text, spanned.span().start);
    let raw = spanned.into_inner();
    let number: u16 = ranged(text, "number", &raw.number, "a PDO number, 1-512")?;
    if !(1..=512).contains(&number) {
        let at = line_of(text, raw.number.span().start);
        return Err(malformed(at, "number", "a PDO number, 1-512"));
    }
    let cob_id = optional(
        text,
        "cob_id",
        raw.cob_id.as_ref(),
        "an 11-bit COB-ID (bit 30 may be set)",
    )?
    .filter(|c: &u32| c & !0x4000_0000 <= 0x7FF);
    if raw.cob_id.is_some() && cob_id.is_none() {
        let at = raw
            .cob_id
            .as_ref()
            .map_or(line, |c| line_of(text, c.span().start));
        return Err(malformed(
            at,
            "cob_id",
            "an 11-bit COB-ID (bit 30 may be set)",
        ));
    }
    Ok(PdoEntry {
        direction,
        number,
        cob_id,
        transmission_type: optional(
            text,
            "transmission_type",
            raw.transmission_type.as_ref(),
            "0-255",
        )?,
        inhibit_time: optional(
            text,
            "inhibit_time",
            raw.inhibit_time.as_ref(),
            "0-65535 (100 µs)",
        )?,
        event_timer: optional(text, "event_timer", raw.event_timer.as_ref(), "0-65535 ms")?,
        mapping: raw
            .mapping
            .into_iter()
            .map(|name| MappedName {
                line: line_of(text, name.span().start),
                name: name.into_inner(),
            })
            .collect(),
        line,
    })
}

/// `value` as a `T`, or refused at its line.
fn ranged<T: TryFrom<i64>>(
    text: &str,
    key: &str,
    value: &Spanned<i64>,
    expected: &'static str,
) -> Result<T, NetworkFileError> {
    T::try_from(*value.get_ref())
        .map_err(|_| malformed(line_of(text, value.span().start), key, expected))
}

fn optional<T: TryFrom<i64>>(
    text: &str,
    key: &str,
    value: Option<&Spanned<i64>>,
    expected: &'static str,
) -> Result<Option<T>, NetworkFileError> {
    value.map(|v| ranged(text, key, v, expected)).transpose()
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

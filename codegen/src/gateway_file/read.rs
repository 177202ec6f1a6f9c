//! Text to [`GatewayFile`]: TOML through serde, then each drive checked for its shape, with the
//! line it is on.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use super::error::{GatewayFileError, GatewayFileErrorKind as Kind};
use super::opcua::{opcua, RawOpcUa};
use super::{
    BusOption, DriveEntry, GatewayFile, MqttEntry, Named, PdoUse, TlsEntry, FORMAT_VERSION,
};
use crate::toml_file::{self, in_file_order, line_of};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    format: Option<Spanned<i64>>,
    #[serde(default)]
    read_only: bool,
    mqtt: Option<Spanned<RawMqtt>>,
    opcua: Option<Spanned<RawOpcUa>>,
    #[serde(default)]
    drive: Vec<Spanned<RawDrive>>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawMqtt {
    host: Option<String>,
    port: Option<Spanned<i64>>,
    topic_prefix: Option<Spanned<String>>,
    username: Option<String>,
    password_env: Option<String>,
    ca_file: Option<String>,
    client_cert_file: Option<String>,
    client_key_file: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDrive {
    name: Spanned<String>,
    description: String,
    bus: BTreeMap<Spanned<String>, toml::Value>,
    interval_ms: Option<Spanned<i64>>,
    #[serde(default)]
    publish_every_poll: bool,
    parameters: Vec<Spanned<String>>,
    #[serde(default)]
    writable: Vec<Spanned<String>>,
    pdo: Option<Spanned<toml::Value>>,
    #[serde(default)]
    pdo_start: bool,
}

/// Reads a gateway file. A file that is not TOML, of another format, without drives, with a
/// drive name twice or unfit for a topic, an OPC UA user twice or none (without `anonymous`), or
/// with an entry of the wrong shape is refused with the line.
pub fn parse(text: &str) -> Result<GatewayFile, GatewayFileError> {
    let raw: RawFile = toml_file::read(text, FORMAT_VERSION, |raw: &RawFile| raw.format.as_ref())
        .map_err(GatewayFileError::unreadable)?;
    if raw.drive.is_empty() {
        return Err(GatewayFileError::at(None, Kind::NoDrives));
    }
    let mut drives: Vec<DriveEntry> = Vec::new();
    for spanned in raw.drive {
        let line = line_of(text, spanned.span().start);
        let drive = drive(text, line, spanned.into_inner())?;
        if drives.iter().any(|d| d.name == drive.name) {
            return Err(GatewayFileError::at(
                Some(line),
                Kind::DuplicateDrive(drive.name),
            ));
        }
        drives.push(drive);
    }
    let opcua = match raw.opcua {
        None => None,
        Some(spanned) => {
            let line = line_of(text, spanned.span().start);
            Some(opcua(text, line, spanned.into_inner())?)
        }
    };
    // MQTT is the default endpoint: on when the file says `[mqtt]`, or names no endpoint.
    let mqtt = match (raw.mqtt, &opcua) {
        (None, Some(_)) => None,
        (raw_mqtt, _) => Some(mqtt(text, raw_mqtt)?),
    };
    Ok(GatewayFile {
        mqtt,
        opcua,
        read_only: raw.read_only,
        drives,
    })
}

fn mqtt(text: &str, raw: Option<Spanned<RawMqtt>>) -> Result<MqttEntry, GatewayFileError> {
    let (line, raw) = match raw {
        Some(spanned) => (
            Some(line_of(text, spanned.span().start)),
            spanned.into_inner(),
        ),
        None => (None, RawMqtt::default()),
    };
    let port = match raw.port {
        None => 1883,
        Some(port) => u16::try_from(*port.get_ref())
            .ok()
            .filter(|p| *p != 0)
            .ok_or_else(|| malformed(line_of(text, port.span().start), "port", "1-65535"))?,
    };
    let topic_prefix = match raw.topic_prefix {
        None => "drivegen".to_owned(),
        Some(prefix) => topic_level(text, prefix, "topic_prefix")?,
    };
    let client = match (raw.client_cert_file, raw.client_key_file) {
        (None, None) => None,
        (Some(cert), Some(key)) => Some((cert, key)),
        _ => {
            return Err(GatewayFileError::at(
                line,
                Kind::Malformed {
                    key: "client_cert_file".into(),
                    expected: "client_cert_file and client_key_file together",
                },
            ))
        }
    };
    let tls = match (raw.ca_file, client) {
        (Some(ca_file), client) => Some(TlsEntry { ca_file, client }),
        (None, None) => None,
        (None, Some(_)) => {
            return Err(GatewayFileError::at(
                line,
                Kind::Malformed {
                    key: "ca_file".into(),
                    expected: "the broker's CA (ca_file) beside a client certificate",
                },
            ))
        }
    };
    Ok(MqttEntry {
        host: raw.host.unwrap_or_else(|| "127.0.0.1".to_owned()),
        port,
        topic_prefix,
        username: raw.username,
        password_env: raw.password_env,
        tls,
    })
}

fn drive(text: &str, line: u32, raw: RawDrive) -> Result<DriveEntry, GatewayFileError> {
    let interval_ms = match raw.interval_ms {
        None => 500,
        Some(ms) => u32::try_from(*ms.get_ref())
            .ok()
            .filter(|ms| *ms >= 1)
            .ok_or_else(|| {
                malformed(
                    line_of(text, ms.span().start),
                    "interval_ms",
                    "at least 1 ms",
                )
            })?,
    };
    if raw.parameters.is_empty() {
        return Err(malformed(line, "parameters", "at least one parameter"));
    }
    let pdo = pdo_use(text, raw.pdo)?;
    if raw.pdo_start && !pdo.on() {
        return Err(malformed(line, "pdo_start", "`pdo = true` beside it"));
    }
    // The event timer (1800h+n sub 5) holds 16 bits of milliseconds.
    if pdo == PdoUse::Event && interval_ms > u32::from(u16::MAX) {
        let expected = "at most 65535 ms with `pdo = \"event\"` (the event timer's 16 bits)";
        return Err(malformed(line, "interval_ms", expected));
    }
    Ok(DriveEntry {
        name: topic_level(text, raw.name, "name")?,
        description: raw.description,
        bus: bus(text, raw.bus)?,
        interval_ms,
        publish_every_poll: raw.publish_every_poll,
        parameters: named(text, raw.parameters),
        writable: named(text, raw.writable),
        pdo,
        pdo_start: raw.pdo_start,
        line,
    })
}

/// The `pdo` key: `true` / `"sync"`, `"event"`, or `false` / none.
fn pdo_use(text: &str, raw: Option<Spanned<toml::Value>>) -> Result<PdoUse, GatewayFileError> {
    let Some(spanned) = raw else {
        return Ok(PdoUse::Off);
    };
    let line = line_of(text, spanned.span().start);
    match spanned.into_inner() {
        toml::Value::Boolean(false) => Ok(PdoUse::Off),
        toml::Value::Boolean(true) => Ok(PdoUse::Sync),
        toml::Value::String(s) if s == "sync" => Ok(PdoUse::Sync),
        toml::Value::String(s) if s == "event" => Ok(PdoUse::Event),
        _ => Err(malformed(
            line,
            "pdo",
            "`true` or `\"sync\"` (a TPDO at each SYNC), `\"event\"` (by its event timer) or `false`",
        )),
    }
}

/// A name that is one topic level: no `/`, `+`, `#`, no spaces, not empty.
fn topic_level(
    text: &str,
    spanned: Spanned<String>,
    key: &str,
) -> Result<String, GatewayFileError> {
    let line = line_of(text, spanned.span().start);
    let name = spanned.into_inner();
    let fits = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
    if fits {
        Ok(name)
    } else {
        Err(malformed(
            line,
            key,
            "a topic level of letters, digits, `-` and `_`",
        ))
    }
}

fn named(text: &str, names: Vec<Spanned<String>>) -> Vec<Named> {
    names
        .into_iter()
        .map(|n| Named {
            line: line_of(text, n.span().start),
            name: n.into_inner(),
        })
        .collect()
}

/// The bus options in the order of the file: strings and numbers as values, `true` as a flag.
fn bus(
    text: &str,
    table: BTreeMap<Spanned<String>, toml::Value>,
) -> Result<Vec<BusOption>, GatewayFileError> {
    in_file_order(text, table)
        .filter_map(|(name, line, value)| {
            let value = match value {
                toml::Value::String(text) => Some(text),
                toml::Value::Integer(int) => Some(int.to_string()),
                toml::Value::Boolean(true) => None,
                toml::Value::Boolean(false) => return None,
                _ => {
                    return Some(Err(malformed(
                        line,
                        &name,
                        "a string, a number or `true`, as the command-line option takes it",
                    )))
                }
            };
            Some(Ok(BusOption { name, value, line }))
        })
        .collect()
}

fn malformed(line: u32, key: &str, expected: &'static str) -> GatewayFileError {
    GatewayFileError::at(
        Some(line),
        Kind::Malformed {
            key: key.to_owned(),
            expected,
        },
    )
}

//! The `[opcua]` table of a gateway file: the OPC UA server endpoint `drivegen gateway` serves
//! (its bind address and port, its PKI directory, anonymous access, the users and their rights,
//! the sampling interval), checked for its shape with the line of each refusal.

use serde::Deserialize;
use toml::Spanned;

use super::error::{GatewayFileError, GatewayFileErrorKind as Kind};
use crate::toml_file::line_of;

/// The OPC UA server endpoint.
#[derive(Debug, Clone, PartialEq)]
pub struct OpcUaEntry {
    /// The address to listen on (default `127.0.0.1`).
    pub host: String,
    /// The port (default 4840, OPC UA's registered port).
    pub port: u16,
    /// The PKI directory, as written (relative to the file, or absolute; default `pki`): the
    /// server's own certificate and key are made there on first start and reused after; the
    /// client certificates it trusts go in its `trusted/certs/`.
    pub pki_dir: String,
    /// Anonymous sessions (which may read, never write) and an endpoint without security beside
    /// the signed and encrypted one (default `false`).
    pub anonymous: bool,
    /// The users who log in with a name and a password.
    pub users: Vec<OpcUaUser>,
    /// The fastest sampling the server offers subscriptions, in milliseconds (default 100).
    pub sampling_interval_ms: u32,
    /// The line of `[opcua]` (1-based).
    pub line: u32,
}

/// One `[[opcua.user]]`.
#[derive(Debug, Clone, PartialEq)]
pub struct OpcUaUser {
    /// The user name.
    pub name: String,
    /// The environment variable holding the password (kept out of the file).
    pub password_env: String,
    /// What the user may do.
    pub right: OpcUaRight,
    /// The line of its `name` (1-based).
    pub line: u32,
}

/// What an OPC UA user may do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OpcUaRight {
    /// Browse, read and subscribe.
    Read,
    /// And write the parameters the drives' `writable` lists name.
    Write,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawOpcUa {
    host: Option<String>,
    port: Option<Spanned<i64>>,
    pki_dir: Option<String>,
    #[serde(default)]
    anonymous: bool,
    sampling_interval_ms: Option<Spanned<i64>>,
    #[serde(default)]
    user: Vec<RawUser>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawUser {
    name: Spanned<String>,
    password_env: String,
    right: Spanned<String>,
}

/// Checks the `[opcua]` table that starts on `line`.
pub(super) fn opcua(text: &str, line: u32, raw: RawOpcUa) -> Result<OpcUaEntry, GatewayFileError> {
    let malformed = |at: usize, key: &str, expected: &'static str| {
        GatewayFileError::at(
            Some(line_of(text, at)),
            Kind::Malformed {
                key: key.to_owned(),
                expected,
            },
        )
    };
    let port = match raw.port {
        None => 4840,
        Some(port) => u16::try_from(*port.get_ref())
            .ok()
            .filter(|p| *p != 0)
            .ok_or_else(|| malformed(port.span().start, "port", "1-65535"))?,
    };
    let sampling_interval_ms = match raw.sampling_interval_ms {
        None => 100,
        Some(ms) => u32::try_from(*ms.get_ref())
            .ok()
            .filter(|ms| *ms >= 1)
            .ok_or_else(|| malformed(ms.span().start, "sampling_interval_ms", "at least 1 ms"))?,
    };
    let mut users: Vec<OpcUaUser> = Vec::new();
    for raw in raw.user {
        let user = user(text, raw)?;
        if users.iter().any(|u| u.name == user.name) {
            return Err(GatewayFileError::at(
                Some(user.line),
                Kind::Malformed {
                    key: "name".into(),
                    expected: "a user name given once",
                },
            ));
        }
        users.push(user);
    }
    if users.is_empty() && !raw.anonymous {
        return Err(GatewayFileError::at(
            Some(line),
            Kind::Malformed {
                key: "opcua".into(),
                expected: "an [[opcua.user]] or `anonymous = true`: no client could log in",
            },
        ));
    }
    Ok(OpcUaEntry {
        host: raw.host.unwrap_or_else(|| "127.0.0.1".to_owned()),
        port,
        pki_dir: raw.pki_dir.unwrap_or_else(|| "pki".to_owned()),
        anonymous: raw.anonymous,
        users,
        sampling_interval_ms,
        line,
    })
}

fn user(text: &str, raw: RawUser) -> Result<OpcUaUser, GatewayFileError> {
    let line = line_of(text, raw.name.span().start);
    let right_line = line_of(text, raw.right.span().start);
    let name = raw.name.into_inner();
    // A name the password login can carry: printable, no spaces, not empty.
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_graphic()) {
        return Err(GatewayFileError::at(
            Some(line),
            Kind::Malformed {
                key: "name".into(),
                expected: "a user name of printable characters without spaces",
            },
        ));
    }
    let right = match raw.right.get_ref().as_str() {
        "read" => OpcUaRight::Read,
        "write" => OpcUaRight::Write,
        _ => {
            return Err(GatewayFileError::at(
                Some(right_line),
                Kind::Malformed {
                    key: "right".into(),
                    expected: "`read` or `write`",
                },
            ))
        }
    };
    Ok(OpcUaUser {
        name,
        password_env: raw.password_env,
        right,
        line,
    })
}

//! The configuration file `drivegen gateway` reads (docs/gateway.md): the MQTT broker to publish
//! to, the OPC UA endpoint to serve, and each drive to expose, with its description, its bus (in the words of the CLI's bus
//! options), the parameters to publish and the ones clients may write. This module is the file
//! alone: text to [`GatewayFile`], every entry with the line it is on; resolving descriptions,
//! parameters and bus options is the CLI's, before any bus is opened.

mod error;
mod opcua;
mod read;
#[cfg(test)]
mod tests;

pub use error::{GatewayFileError, GatewayFileErrorKind};
pub use opcua::{OpcUaEntry, OpcUaRight, OpcUaUser};
pub use read::parse;

/// The version of the file format this module reads (`format = 1`).
pub const FORMAT_VERSION: u32 = 1;

/// A gateway: where to publish, and the drives.
#[derive(Debug, Clone, PartialEq)]
pub struct GatewayFile {
    /// The `[mqtt]` table: its defaults when the file has neither `[mqtt]` nor `[opcua]`,
    /// `None` when it has `[opcua]` alone (a gateway for OPC UA clients only).
    pub mqtt: Option<MqttEntry>,
    /// The `[opcua]` table, when the file has one.
    pub opcua: Option<OpcUaEntry>,
    /// Refuse every write, whatever the drives' `writable` lists say.
    pub read_only: bool,
    /// The `[[drive]]` entries, in the file's order.
    pub drives: Vec<DriveEntry>,
}

/// The MQTT broker the gateway publishes to.
#[derive(Debug, Clone, PartialEq)]
pub struct MqttEntry {
    /// Its host (default `127.0.0.1`).
    pub host: String,
    /// Its port (default 1883).
    pub port: u16,
    /// The first topic level (default `drivegen`).
    pub topic_prefix: String,
    /// The user name to log in with, if the broker asks for one.
    pub username: Option<String>,
    /// The environment variable holding the password (kept out of the file).
    pub password_env: Option<String>,
    /// TLS to the broker, when the file names a CA.
    pub tls: Option<TlsEntry>,
}

/// TLS to the broker: the CA that signed its certificate, and the gateway's own certificate when
/// the broker asks for one. Paths as written (relative to the file, or absolute), PEM files.
#[derive(Debug, Clone, PartialEq)]
pub struct TlsEntry {
    /// `ca_file`.
    pub ca_file: String,
    /// `client_cert_file` and `client_key_file`, given together.
    pub client: Option<(String, String)>,
}

/// One `[[drive]]`.
#[derive(Debug, Clone, PartialEq)]
pub struct DriveEntry {
    /// Its name: the topic level after the prefix (letters, digits, `-` and `_`).
    pub name: String,
    /// Its description, as written (a path relative to the file, or absolute).
    pub description: String,
    /// How to reach it: the CLI's bus options without their `--` (`modbus_tcp = "HOST:PORT"`,
    /// `unit = 3`, `can = "slcan:..."`, `node_id = 5`, `timeout_ms = 200`), in the file's order.
    pub bus: Vec<BusOption>,
    /// Milliseconds between polls (default 500).
    pub interval_ms: u32,
    /// Publish every poll (`true`), or only the values that changed (default).
    pub publish_every_poll: bool,
    /// The parameters to publish.
    pub parameters: Vec<Named>,
    /// The parameters clients may write (default none).
    pub writable: Vec<Named>,
    /// CANopen: take the values from a TPDO, as `drivegen watch --pdo` does: at each SYNC the
    /// gateway sends (`pdo = true` or `pdo = "sync"`), or by the drive's event timer every
    /// `interval_ms` (`pdo = "event"`); default: SDO polls.
    pub pdo: PdoUse,
    /// With `pdo`: send NMT Start to the node before (a node sends PDOs only while
    /// Operational) and Enter Pre-Operational after (`pdo_start = true`), as `watch --start`.
    pub pdo_start: bool,
    /// The line of its `[[drive]]` (1-based).
    pub line: u32,
}

/// How a drive's values come (its `pdo` key).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PdoUse {
    /// By SDO polls (`pdo = false`, or no `pdo`).
    #[default]
    Off,
    /// By a TPDO the drive sends at each SYNC the gateway sends (`pdo = true`, `pdo = "sync"`).
    Sync,
    /// By a TPDO the drive sends by its event timer every `interval_ms`, no SYNC sent for it
    /// (`pdo = "event"`).
    Event,
}

impl PdoUse {
    /// Whether the values come by TPDO at all.
    pub fn on(self) -> bool {
        self != Self::Off
    }
}

/// One bus option: its name (`modbus_tcp`) and its value as the command line would take it; a
/// flag set to `true` has no value.
#[derive(Debug, Clone, PartialEq)]
pub struct BusOption {
    /// The option's name, with `_` where the command line has `-`.
    pub name: String,
    /// Its value; `None` for a flag.
    pub value: Option<String>,
    /// The line it is on (1-based).
    pub line: u32,
}

/// A name with the line it is on.
#[derive(Debug, Clone, PartialEq)]
pub struct Named {
    /// The name.
    pub name: String,
    /// The line (1-based).
    pub line: u32,
}

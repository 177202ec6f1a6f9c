//! The configuration backup file `drivegen config pull` writes and `config push` / `config
//! compare` read (docs/config-file.md): a drive's readable and writable parameters in
//! engineering units with their raw values, the identity read, and the description they were
//! read with. This module is the file alone: text to [`ConfigFile`] and back, every entry with
//! the line it is on; checking the entries against a description is the CLI's.

mod error;
mod read;
mod write;

pub use error::{ConfigFileError, ConfigFileErrorKind};
pub use read::parse;
pub use write::render;

/// The version of the file format this module reads and writes (`format = 1`).
pub const FORMAT_VERSION: u32 = 1;

/// A configuration backup.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigFile {
    /// The description the values were read with.
    pub description: DescriptionRef,
    /// Where and when they were read.
    pub drive: DriveRecord,
    /// The identity parameters read, raw.
    pub identity: Vec<IdentityEntry>,
    /// The parameters read, in the description's order.
    pub parameters: Vec<SavedParameter>,
    /// The readable and writable parameters that were not read, each with the reason.
    pub unread: Vec<Unread>,
}

/// The description a backup was read with.
#[derive(Debug, Clone, PartialEq)]
pub struct DescriptionRef {
    /// The device name (`[device] name`).
    pub name: String,
    /// The firmware the description documents (`[device] firmware`), if it names one.
    pub firmware: Option<String>,
    /// The description's path when it was read, for `push` and `compare` to load it again.
    pub path: Option<String>,
}

/// Where and when a backup was read.
#[derive(Debug, Clone, PartialEq)]
pub struct DriveRecord {
    /// The bus and address (`Modbus TCP 127.0.0.1:502 unit 1`).
    pub target: String,
    /// The description's variant the drive was in, for a description with variants.
    pub variant: Option<String>,
    /// When, in UTC (RFC 3339, `2026-11-27T21:40:00Z`).
    pub pulled_at: String,
}

/// One identity parameter and the raw value it held.
#[derive(Debug, Clone, PartialEq)]
pub struct IdentityEntry {
    /// The parameter.
    pub name: String,
    /// Its raw value.
    pub raw: i128,
    /// The line of the file it is on (1-based; 0 when not from a file).
    pub line: u32,
}

/// One parameter's value.
#[derive(Debug, Clone, PartialEq)]
pub struct SavedParameter {
    /// The parameter.
    pub name: String,
    /// The value in engineering units as `drivegen read` shows it and `drivegen write` takes it
    /// (`15.00 s`, `velocity`, `raw 4950` for a run-time scale).
    pub value: String,
    /// The raw value read.
    pub raw: SavedRaw,
    /// The unit, for people (the value carries it too).
    pub unit: Option<String>,
    /// The line of the file it is on (1-based; 0 when not from a file).
    pub line: u32,
}

/// A raw value as the file keeps it.
#[derive(Debug, Clone, PartialEq)]
pub enum SavedRaw {
    /// An integer, exact (in the file: an integer, or a decimal string beyond 64 bits).
    Int(i128),
    /// A floating-point value.
    Float(f64),
    /// The bytes of a string or octet parameter.
    Bytes(Vec<u8>),
}

/// A readable and writable parameter that was not read, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct Unread {
    /// The parameter.
    pub name: String,
    /// Why it was not read.
    pub reason: String,
    /// The line of the file it is on (1-based; 0 when not from a file).
    pub line: u32,
}

impl ConfigFile {
    /// The saved parameter called `name`.
    pub fn parameter(&self, name: &str) -> Option<&SavedParameter> {
        self.parameters.iter().find(|p| p.name == name)
    }
}

#[cfg(test)]
mod tests;

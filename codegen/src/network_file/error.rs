//! Why a network file was refused, with the line it points at.

use std::fmt;

use crate::file_error::{unreadable_kind, unsupported_format, FileError};

/// A network file that cannot be read, with the line it points at.
pub type NetworkFileError = FileError<NetworkFileErrorKind>;

/// What is wrong with a network file.
#[derive(Debug, Clone, PartialEq)]
pub enum NetworkFileErrorKind {
    /// Not TOML, an unknown key, or a value of the wrong type.
    Syntax(String),
    /// A `format` this version does not read.
    UnsupportedFormat(i64),
    /// `format` is missing.
    MissingFormat,
    /// No `[[node]]` at all.
    NoNodes,
    /// A node id outside 1-127.
    NodeIdOutOfRange(i64),
    /// Two `[[node]]` with the same id.
    DuplicateNode(u8),
    /// A PDO the drive does not have: its description has no communication object for it.
    PdoAbsent {
        /// `TPDO n` or `RPDO n`.
        pdo: String,
        /// Its communication object (1800h/1400h + n − 1).
        index: u16,
    },
    /// A PDO setting whose sub-index the drive's description does not have.
    PdoSettingAbsent {
        /// `TPDO n` or `RPDO n`.
        pdo: String,
        /// The key (`transmission_type`, `inhibit_time`, `event_timer`).
        key: &'static str,
        /// The communication object.
        index: u16,
        /// The missing sub-index.
        subindex: u8,
    },
    /// A PDO beyond 4 without a `cob_id`: the predefined connection set gives none.
    PdoNoCobId {
        /// `TPDO n` or `RPDO n`.
        pdo: String,
    },
    /// A mapped parameter the description does not have.
    PdoUnknownParameter {
        /// Its name.
        name: String,
    },
    /// A mapped parameter that is not PDO-mappable in its description.
    PdoNotMappable {
        /// Its name.
        name: String,
    },
    /// A mapped parameter mappable only in the other direction.
    PdoWrongDirection {
        /// Its name.
        name: String,
        /// `TPDO` or `RPDO`: the PDO it was mapped into.
        wanted: &'static str,
    },
    /// A mapping longer than the 64 bits a PDO carries.
    PdoTooManyBits {
        /// `TPDO n` or `RPDO n`.
        pdo: String,
        /// The mapping's bits.
        bits: u32,
    },
    /// More mapped parameters than the drive's mapping object has entries.
    PdoTooManyEntries {
        /// `TPDO n` or `RPDO n`.
        pdo: String,
        /// Mapped parameters.
        entries: usize,
        /// Entries of the mapping object.
        capacity: usize,
        /// The mapping object.
        index: u16,
    },
    /// An entry of the wrong shape or out of its range.
    Malformed {
        /// The key.
        key: String,
        /// What was expected.
        expected: &'static str,
    },
}

unreadable_kind!(NetworkFileErrorKind);

impl fmt::Display for NetworkFileErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NetworkFileErrorKind::Syntax(why) => write!(f, "not a network file: {why}"),
            NetworkFileErrorKind::UnsupportedFormat(found) => {
                unsupported_format(f, *found, super::FORMAT_VERSION)
            }
            NetworkFileErrorKind::MissingFormat => f.write_str("`format = 1` is missing"),
            NetworkFileErrorKind::NoNodes => f.write_str("no [[node]]: nothing to boot"),
            NetworkFileErrorKind::NodeIdOutOfRange(id) => {
                write!(f, "node id {id} is outside 1-127")
            }
            NetworkFileErrorKind::DuplicateNode(id) => {
                write!(f, "node {id} appears twice")
            }
            NetworkFileErrorKind::PdoAbsent { pdo, index } => write!(
                f,
                "the drive has no {pdo}: its description has no object {index:04X}h"
            ),
            NetworkFileErrorKind::PdoSettingAbsent {
                pdo,
                key,
                index,
                subindex,
            } => write!(
                f,
                "{pdo}: `{key}` cannot be set: the description has no {index:04X}h sub {subindex}"
            ),
            NetworkFileErrorKind::PdoNoCobId { pdo } => write!(
                f,
                "{pdo}: give `cob_id` (the predefined connection set covers PDOs 1-4)"
            ),
            NetworkFileErrorKind::PdoUnknownParameter { name } => {
                write!(f, "PDO mapping: no parameter `{name}` in the description")
            }
            NetworkFileErrorKind::PdoNotMappable { name } => write!(
                f,
                "PDO mapping: `{name}` is not PDO-mappable in the description"
            ),
            NetworkFileErrorKind::PdoWrongDirection { name, wanted } => write!(
                f,
                "PDO mapping: `{name}` cannot be mapped into a {wanted} (the description maps it the other way)"
            ),
            NetworkFileErrorKind::PdoTooManyBits { pdo, bits } => write!(
                f,
                "{pdo}: the mapping takes {bits} bits; a PDO carries 64"
            ),
            NetworkFileErrorKind::PdoTooManyEntries {
                pdo,
                entries,
                capacity,
                index,
            } => write!(
                f,
                "{pdo}: {entries} parameters mapped; the drive's mapping object {index:04X}h has {capacity} entries"
            ),
            NetworkFileErrorKind::Malformed { key, expected } => {
                write!(f, "`{key}`: expected {expected}")
            }
        }
    }
}

//! Why a gateway file was refused, with the line it points at.

use std::fmt;

use crate::file_error::{unreadable_kind, unsupported_format, FileError};

/// A gateway file that cannot be read, with the line it points at.
pub type GatewayFileError = FileError<GatewayFileErrorKind>;

/// What is wrong with a gateway file.
#[derive(Debug, Clone, PartialEq)]
pub enum GatewayFileErrorKind {
    /// Not TOML, an unknown key, or a value of the wrong type.
    Syntax(String),
    /// A `format` this version does not read.
    UnsupportedFormat(i64),
    /// `format` is missing.
    MissingFormat,
    /// No `[[drive]]` at all.
    NoDrives,
    /// Two `[[drive]]` with the same name.
    DuplicateDrive(String),
    /// An entry of the wrong shape or out of its range.
    Malformed {
        /// The key.
        key: String,
        /// What was expected.
        expected: &'static str,
    },
}

unreadable_kind!(GatewayFileErrorKind);

impl fmt::Display for GatewayFileErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GatewayFileErrorKind::Syntax(why) => write!(f, "not a gateway file: {why}"),
            GatewayFileErrorKind::UnsupportedFormat(found) => {
                unsupported_format(f, *found, super::FORMAT_VERSION)
            }
            GatewayFileErrorKind::MissingFormat => f.write_str("`format = 1` is missing"),
            GatewayFileErrorKind::NoDrives => f.write_str("no [[drive]]: nothing to expose"),
            GatewayFileErrorKind::DuplicateDrive(name) => {
                write!(f, "drive `{name}` appears twice")
            }
            GatewayFileErrorKind::Malformed { key, expected } => {
                write!(f, "`{key}`: expected {expected}")
            }
        }
    }
}

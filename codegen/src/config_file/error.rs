//! Why a configuration file was refused, with the line it points at.

use std::fmt;

use crate::file_error::{unsupported_format, FileError, UnreadableKind};

/// A configuration file that cannot be read, with the line it points at.
pub type ConfigFileError = FileError<ConfigFileErrorKind>;

/// What is wrong with a configuration file.
#[derive(Debug, Clone, PartialEq)]
pub enum ConfigFileErrorKind {
    /// Not TOML, or cut short (a truncated file ends inside a value or a table).
    Syntax(String),
    /// A `format` this version does not read.
    UnsupportedFormat(i64),
    /// A table or key the format requires is missing (a file cut short between tables).
    Missing(&'static str),
    /// An entry of the wrong shape.
    Malformed {
        /// The key.
        key: String,
        /// What was expected.
        expected: &'static str,
    },
    /// The same parameter saved twice, or both saved and listed unread.
    Duplicate(String),
}

impl UnreadableKind for ConfigFileErrorKind {
    fn syntax(why: String) -> Self {
        Self::Syntax(why)
    }

    fn missing_format() -> Self {
        Self::Missing("format")
    }

    fn unsupported_format(found: i64) -> Self {
        Self::UnsupportedFormat(found)
    }
}

impl fmt::Display for ConfigFileErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ConfigFileErrorKind::Syntax(why) => write!(f, "not a configuration file: {why}"),
            ConfigFileErrorKind::UnsupportedFormat(found) => {
                unsupported_format(f, *found, super::FORMAT_VERSION)
            }
            ConfigFileErrorKind::Missing(what) => {
                write!(f, "`{what}` is missing (is the file cut short?)")
            }
            ConfigFileErrorKind::Malformed { key, expected } => {
                write!(f, "`{key}`: expected {expected}")
            }
            ConfigFileErrorKind::Duplicate(name) => write!(f, "`{name}` appears twice"),
        }
    }
}

//! Why a configuration file was refused, with the line it points at.

use std::fmt;

/// A configuration file that cannot be read.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigFileError {
    /// The line (1-based) the error is on, when it is on one.
    pub line: Option<u32>,
    /// What is wrong.
    pub kind: ConfigFileErrorKind,
}

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

impl ConfigFileError {
    /// What is wrong, without the line (for messages that put the line elsewhere).
    pub fn kind_text(&self) -> String {
        Self {
            line: None,
            kind: self.kind.clone(),
        }
        .to_string()
    }

    pub(super) fn at(line: Option<u32>, kind: ConfigFileErrorKind) -> Self {
        Self { line, kind }
    }
}

impl fmt::Display for ConfigFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(line) = self.line {
            write!(f, "line {line}: ")?;
        }
        match &self.kind {
            ConfigFileErrorKind::Syntax(why) => write!(f, "not a configuration file: {why}"),
            ConfigFileErrorKind::UnsupportedFormat(found) => write!(
                f,
                "format {found} is not read by this drivegen (it reads format {})",
                super::FORMAT_VERSION
            ),
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

impl std::error::Error for ConfigFileError {}

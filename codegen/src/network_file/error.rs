//! Why a network file was refused, with the line it points at.

use std::fmt;

/// A network file that cannot be read.
#[derive(Debug, Clone, PartialEq)]
pub struct NetworkFileError {
    /// The line (1-based) the error is on, when it is on one.
    pub line: Option<u32>,
    /// What is wrong.
    pub kind: NetworkFileErrorKind,
}

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
    /// An entry of the wrong shape or out of its range.
    Malformed {
        /// The key.
        key: String,
        /// What was expected.
        expected: &'static str,
    },
}

impl NetworkFileError {
    pub(super) fn at(line: Option<u32>, kind: NetworkFileErrorKind) -> Self {
        Self { line, kind }
    }
}

impl fmt::Display for NetworkFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(line) = self.line {
            write!(f, "line {line}: ")?;
        }
        match &self.kind {
            NetworkFileErrorKind::Syntax(why) => write!(f, "not a network file: {why}"),
            NetworkFileErrorKind::UnsupportedFormat(found) => write!(
                f,
                "format {found} is not read by this drivegen (it reads format {})",
                super::FORMAT_VERSION
            ),
            NetworkFileErrorKind::MissingFormat => f.write_str("`format = 1` is missing"),
            NetworkFileErrorKind::NoNodes => f.write_str("no [[node]]: nothing to boot"),
            NetworkFileErrorKind::NodeIdOutOfRange(id) => {
                write!(f, "node id {id} is outside 1-127")
            }
            NetworkFileErrorKind::DuplicateNode(id) => {
                write!(f, "node {id} appears twice")
            }
            NetworkFileErrorKind::Malformed { key, expected } => {
                write!(f, "`{key}`: expected {expected}")
            }
        }
    }
}

impl std::error::Error for NetworkFileError {}

//! Why a gateway file was refused, with the line it points at.

use std::fmt;

/// A gateway file that cannot be read.
#[derive(Debug, Clone, PartialEq)]
pub struct GatewayFileError {
    /// The line (1-based) the error is on, when it is on one.
    pub line: Option<u32>,
    /// What is wrong.
    pub kind: GatewayFileErrorKind,
}

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

impl GatewayFileError {
    /// What is wrong, without the line (for messages that put the line elsewhere).
    pub fn kind_text(&self) -> String {
        Self {
            line: None,
            kind: self.kind.clone(),
        }
        .to_string()
    }

    pub(super) fn at(line: Option<u32>, kind: GatewayFileErrorKind) -> Self {
        Self { line, kind }
    }
}

impl fmt::Display for GatewayFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(line) = self.line {
            write!(f, "line {line}: ")?;
        }
        match &self.kind {
            GatewayFileErrorKind::Syntax(why) => write!(f, "not a gateway file: {why}"),
            GatewayFileErrorKind::UnsupportedFormat(found) => write!(
                f,
                "format {found} is not read by this drivegen (it reads format {})",
                super::FORMAT_VERSION
            ),
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

impl std::error::Error for GatewayFileError {}

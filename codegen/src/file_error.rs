//! The error of the TOML files drivegen's commands read (configuration backups, network and
//! gateway files): what is wrong, in the terms of the file's own format, and the line it is on.

use std::fmt;

use crate::toml_file::Unreadable;

/// A file that cannot be read: `kind` says what is wrong, `line` where.
#[derive(Debug, Clone, PartialEq)]
pub struct FileError<K> {
    /// The line (1-based) the error is on, when it is on one.
    pub line: Option<u32>,
    /// What is wrong.
    pub kind: K,
}

impl<K> FileError<K> {
    pub(crate) fn at(line: Option<u32>, kind: K) -> Self {
        Self { line, kind }
    }

    /// A file that is not TOML, or of no or another format version.
    pub(crate) fn unreadable(unreadable: Unreadable) -> Self
    where
        K: UnreadableKind,
    {
        match unreadable {
            Unreadable::Syntax(line, why) => Self::at(line, K::syntax(why)),
            Unreadable::MissingFormat => Self::at(None, K::missing_format()),
            Unreadable::UnsupportedFormat(line, found) => {
                Self::at(Some(line), K::unsupported_format(found))
            }
        }
    }
}

impl<K: fmt::Display> FileError<K> {
    /// What is wrong, without the line (for messages that put the line elsewhere).
    pub fn kind_text(&self) -> String {
        self.kind.to_string()
    }
}

impl<K: fmt::Display> fmt::Display for FileError<K> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(line) = self.line {
            write!(f, "line {line}: ")?;
        }
        self.kind.fmt(f)
    }
}

impl<K: fmt::Debug + fmt::Display> std::error::Error for FileError<K> {}

/// The kinds of error every file format has for a file it cannot read at all.
pub(crate) trait UnreadableKind {
    /// Not TOML, an unknown key, or a value of the wrong type.
    fn syntax(why: String) -> Self;
    /// No `format`.
    fn missing_format() -> Self;
    /// A `format` this version does not read.
    fn unsupported_format(found: i64) -> Self;
}

/// [`UnreadableKind`] for a kind with the variants `Syntax(String)`, `MissingFormat` and
/// `UnsupportedFormat(i64)` (the network and gateway files; the configuration file says
/// "missing" of any key, `format` included).
macro_rules! unreadable_kind {
    ($kind:ty) => {
        impl $crate::file_error::UnreadableKind for $kind {
            fn syntax(why: String) -> Self {
                Self::Syntax(why)
            }

            fn missing_format() -> Self {
                Self::MissingFormat
            }

            fn unsupported_format(found: i64) -> Self {
                Self::UnsupportedFormat(found)
            }
        }
    };
}
pub(crate) use unreadable_kind;

/// "format N is not read by this drivegen (it reads format V)".
pub(crate) fn unsupported_format(
    f: &mut fmt::Formatter<'_>,
    found: i64,
    reads: u32,
) -> fmt::Result {
    write!(
        f,
        "format {found} is not read by this drivegen (it reads format {reads})"
    )
}

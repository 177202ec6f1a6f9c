//! Class of a drive error code: whether the drive stops (fault) or only signals (warning).
//!
//! Generated error-code enumerations return it from `class()` when their description gives each
//! value a `class`.

/// Whether an error code stops the drive or only warns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ErrorClass {
    /// The drive stops (alarm state) and needs a fault reset.
    Fault,
    /// The drive keeps running and signals the condition.
    Warning,
}

impl core::fmt::Display for ErrorClass {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Self::Fault => "fault",
            Self::Warning => "warning",
        })
    }
}

//! The CLI's errors: each says what was wrong and, where it can, what to do.

use std::fmt;

use drivebus::BusError;

use drivebus::interpret::InputError;

/// A failed command.
#[derive(Debug)]
pub enum CliError {
    /// The description has errors (already rendered).
    Invalid(String),
    /// No parameter of this name; the closest names.
    UnknownParameter {
        /// The name given.
        name: String,
        /// Suggestions.
        closest: Vec<String>,
    },
    /// A value was refused before anything was sent.
    Value {
        /// Parameter.
        parameter: String,
        /// Why.
        cause: InputError,
        /// Where the description's value comes from (`manual.txt line 889`), if cited.
        cited: Option<String>,
    },
    /// The parameter has no address on the chosen protocol, or not with this access.
    NoAccess(String),
    /// The bus failed or the drive refused.
    Bus {
        /// Where: address and unit / node.
        target: String,
        /// Parameter accessed.
        parameter: String,
        /// What happened.
        cause: BusError,
    },
    /// Wrong command-line usage.
    Usage(String),
    /// I/O on files or sockets.
    Io(String),
    /// The drive's identity parameter holds a value the description does not cover; nothing
    /// was written.
    IdentityMismatch {
        /// The identity parameter.
        parameter: String,
        /// The values the description covers.
        expected: drivegen::ir::Covered,
        /// The raw value the drive reported.
        found: String,
    },
    /// `diff` found changes that break code written against the old description.
    Breaking(usize),
    /// The value lies beyond the current value of a parameter that bounds it; nothing was
    /// written.
    OutsideBound(String),
    /// The drive's variant is not known (or the parameter is not in it) and the parameter's
    /// address depends on it; nothing was sent.
    Variant(String),
    /// A configuration file refused before anything was sent: the file, the line, why.
    ConfigFile {
        /// The file.
        file: String,
        /// The line the reason is about, when it is about one.
        line: Option<u32>,
        /// Why.
        reason: String,
    },
    /// The drive is not the one (or not in the firmware or variant) a configuration file was
    /// read from; nothing was written.
    ForeignDrive(String),
    /// `config compare` found this many differences.
    Differs(usize),
    /// Some of the drives `read` or `watch` asked did not answer (their errors are shown).
    DrivesFailed {
        /// Drives that failed (in `watch`: at least once).
        failed: usize,
        /// Drives asked.
        asked: usize,
    },
    /// `config push` could not write (or verify) this many of the parameters it meant to.
    PushIncomplete {
        /// Parameters refused or not read back as written.
        refused: usize,
        /// Parameters the push meant to write.
        planned: usize,
    },
    /// A CAN interface or adapter could not be opened.
    CanOpen {
        /// The `--can` value.
        spec: String,
        /// The bit rate of the command, for the `ip link` hint.
        bitrate: u32,
        /// Why.
        error: drivebus::canopen::can::OpenError,
    },
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Invalid(text) => write!(f, "{text}"),
            CliError::UnknownParameter { name, closest } if closest.is_empty() => {
                write!(f, "no parameter named `{name}`")
            }
            CliError::UnknownParameter { name, closest } => write!(
                f,
                "no parameter named `{name}`; did you mean {}?",
                closest
                    .iter()
                    .map(|c| format!("`{c}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            CliError::Value {
                parameter,
                cause,
                cited: None,
            } => write!(f, "{parameter}: {cause} (nothing was sent)"),
            CliError::Value {
                parameter,
                cause,
                cited: Some(cited),
            } => write!(f, "{parameter}: {cause}, as {cited} gives it (nothing was sent)"),
            CliError::NoAccess(why) => write!(f, "{why}"),
            CliError::Bus {
                target,
                parameter,
                cause: BusError::Timeout,
            } => write!(f, "{parameter}: no answer from {target} (timeout)"),
            CliError::Bus {
                target,
                parameter,
                cause,
            } => write!(f, "{parameter}: {target}: {cause}"),
            CliError::Usage(text) | CliError::Io(text) => write!(f, "{text}"),
            CliError::OutsideBound(why) => write!(f, "{why} (nothing was written)"),
            CliError::Variant(why) => write!(f, "{why} (nothing was sent)"),
            CliError::CanOpen {
                spec,
                bitrate,
                error,
            } => f.write_str(&crate::can::describe(spec, *bitrate, error)),
            CliError::IdentityMismatch {
                parameter,
                expected,
                found,
            } => write!(
                f,
                "{parameter} reads {found}, the description covers {expected}: not written (--no-identity-check writes anyway)"
            ),
            CliError::ConfigFile {
                file,
                line: Some(line),
                reason,
            } => write!(f, "{file}:{line}: {reason} (nothing was sent)"),
            CliError::ConfigFile {
                file,
                line: None,
                reason,
            } => write!(f, "{file}: {reason} (nothing was sent)"),
            CliError::ForeignDrive(why) => write!(f, "{why}: nothing was written"),
            CliError::Differs(count) => write!(f, "{count} difference(s)"),
            CliError::DrivesFailed { failed, asked } => write!(
                f,
                "{failed} of {asked} drives failed (see their columns above)"
            ),
            CliError::PushIncomplete { refused, planned } => write!(
                f,
                "{refused} of {planned} parameter(s) not written as the file holds them (see the report above)"
            ),
            CliError::Breaking(count) => write!(
                f,
                "{count} breaking change(s): code written against the old description may not compile"
            ),
        }
    }
}

impl std::error::Error for CliError {}

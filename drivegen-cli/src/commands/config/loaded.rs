//! A configuration file read and checked against its description before anything is sent:
//! the description it names (or `--description`), every entry a configuration parameter of it,
//! every value within its type, range and allowed values. Each refusal names the file and line.

use std::path::{Path, PathBuf};

use drivebus::interpret;
use drivegen::config_file::{self, ConfigFile, SavedParameter, SavedRaw};
use drivegen::ir::{Device, Parameter};

use super::selection;
use crate::error::CliError;
use crate::suggest;

/// A configuration file and the description it is read with.
pub struct Loaded {
    /// The file's path, for messages.
    pub path: String,
    /// Its contents.
    pub file: ConfigFile,
    /// The description.
    pub device: Device,
}

/// A value a file holds for a parameter, as the raw bytes to write.
pub struct Desired<'d> {
    /// The parameter.
    pub parameter: &'d Parameter,
    /// Its raw value, little-endian.
    pub bytes: Vec<u8>,
    /// The file line it comes from.
    pub line: u32,
    /// Why the value, as read from a drive and not edited, is not one the description allows
    /// (a drive may hold such a value): it is compared, and refused only where it would be
    /// written.
    pub invalid: Option<String>,
}

impl Loaded {
    /// Reads `file` and loads the description it names, or `description`.
    pub fn open(file: &Path, description: Option<&Path>) -> Result<Self, CliError> {
        let path = file.display().to_string();
        let text = std::fs::read_to_string(file)
            .map_err(|e| CliError::Io(format!("cannot read {path}: {e}")))?;
        let parsed = config_file::parse(&text).map_err(|e| CliError::ConfigFile {
            file: path.clone(),
            line: e.line,
            reason: e.kind_text(),
        })?;
        let description = match (description, &parsed.description.path) {
            (Some(given), _) => given.to_path_buf(),
            (None, Some(named)) => PathBuf::from(named),
            (None, None) => {
                return Err(CliError::Usage(format!(
                    "{path} names no description path: give --description"
                )))
            }
        };
        let device = crate::commands::load(&description)?;
        let loaded = Self {
            path,
            file: parsed,
            device,
        };
        loaded.check_description()?;
        Ok(loaded)
    }

    /// A refusal about line `line` of the file.
    pub fn refuse(&self, line: Option<u32>, reason: String) -> CliError {
        CliError::ConfigFile {
            file: self.path.clone(),
            line,
            reason,
        }
    }

    /// The file was read with a description of this device and firmware.
    fn check_description(&self) -> Result<(), CliError> {
        let named = &self.file.description;
        let ours = &self.device.device;
        if named.name != ours.name {
            return Err(self.refuse(
                None,
                format!(
                    "the file was read from a {} drive, the description is of {}",
                    named.name, ours.name
                ),
            ));
        }
        if named.firmware.is_some() && ours.firmware.is_some() && named.firmware != ours.firmware {
            return Err(self.refuse(
                None,
                format!(
                    "the file was read with the description of firmware {}, this one is of {}",
                    named.firmware.as_deref().unwrap_or_default(),
                    ours.firmware.as_deref().unwrap_or_default()
                ),
            ));
        }
        Ok(())
    }

    /// Every saved value as the bytes to write, or the first entry refused.
    pub fn desired(&self) -> Result<Vec<Desired<'_>>, CliError> {
        self.file
            .parameters
            .iter()
            .map(|saved| self.desired_one(saved))
            .collect()
    }

    fn desired_one<'d>(&'d self, saved: &SavedParameter) -> Result<Desired<'d>, CliError> {
        let line = Some(saved.line);
        let parameter = self.device.parameter(&saved.name).ok_or_else(|| {
            let closest = suggest::closest(
                &saved.name,
                self.device.parameters.iter().map(|p| p.name.as_str()),
            );
            let hint = match closest.first() {
                Some(close) => format!("; did you mean `{close}`?"),
                None => String::new(),
            };
            self.refuse(
                line,
                format!(
                    "`{}` is not a parameter of {}{hint}",
                    saved.name, self.device.device.name
                ),
            )
        })?;
        if !selection::is_configuration(&self.device, parameter) {
            return Err(self.refuse(
                line,
                format!(
                    "`{}` is not a configuration parameter of {} (not readable and writable, or a command)",
                    saved.name, self.device.device.name
                ),
            ));
        }
        let refusal = |cause| self.refuse(line, format!("{}: {cause}", saved.name));
        let (bytes, invalid) = match value_bytes(&self.device, parameter, saved) {
            Ok(bytes) => (bytes, None),
            Err(Edited::No { exact, cause }) => (exact, Some(cause.to_string())),
            Err(Edited::Yes(cause)) => return Err(refusal(cause)),
        };
        Ok(Desired {
            parameter,
            bytes,
            line: saved.line,
            invalid,
        })
    }
}

/// A value refused by the description's checks.
enum Edited {
    /// The raw value as read, whose `value` text is unedited: its exact bytes.
    No {
        exact: Vec<u8>,
        cause: interpret::InputError,
    },
    /// An edited value.
    Yes(interpret::InputError),
}

/// The raw bytes a saved value stands for. While `value` is the text the raw value shows as,
/// the raw value is written exactly; an edited `value` is parsed as `drivegen write` parses it.
/// Either way it is checked against the parameter's type, range and allowed values.
fn value_bytes(
    device: &Device,
    parameter: &Parameter,
    saved: &SavedParameter,
) -> Result<Vec<u8>, Edited> {
    let typed = |text: &str| interpret::parse(device, parameter, text);
    let edited = |text: &str| typed(text).map_err(Edited::Yes);
    let (exact, check) = match &saved.raw {
        SavedRaw::Int(raw) => {
            let exact = interpret::raw::from_int(parameter.data_type, *raw);
            let fits = interpret::raw::to_int(parameter.data_type, &exact) == Some(*raw);
            (exact, fits.then(|| format!("raw:{raw}")))
        }
        SavedRaw::Bytes(bytes) => (bytes.clone(), Some(String::from_utf8_lossy(bytes).into())),
        SavedRaw::Float(_) => return edited(&saved.value),
    };
    let unedited = interpret::show(device, parameter, &exact).text == saved.value;
    match (unedited, check) {
        (true, Some(check)) => match typed(&check) {
            Ok(_) => Ok(exact),
            Err(cause) => Err(Edited::No { exact, cause }),
        },
        // A raw value beyond its type is refused as typed.
        (true, None) => typed(&saved.value).map_err(Edited::Yes),
        (false, _) => edited(&saved.value),
    }
}

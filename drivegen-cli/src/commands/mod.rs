//! One file per subcommand, and what they share: loading a description, finding parameters.

pub mod check;
pub mod config;
pub mod dbc;
pub mod decode;
pub mod diff;
pub mod dump;
pub mod eds;
pub mod gateway;
pub mod generate;
pub mod lss;
pub mod network;
pub mod new;
pub mod read;
pub mod safety;
pub mod scan;
pub mod sim;
pub mod trace;
pub mod watch;
pub mod write;

use std::path::Path;

use drivegen::ir::{Device, Parameter};

use crate::error::CliError;
use crate::suggest;

/// The drivebus version generated code is written against.
pub const DRIVEBUS_VERSION: &str = "0.1";

/// The drivegen version a new drive crate's build script uses.
pub const DRIVEGEN_VERSION: &str = "0.1";

/// Writes `text` to `path` and says so on standard error.
pub fn write_file(path: &Path, text: &str) -> Result<(), CliError> {
    std::fs::write(path, text)
        .map_err(|e| CliError::Io(format!("cannot write {}: {e}", path.display())))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// Loads and validates a description; warnings go to stderr.
pub fn load(description: &Path) -> Result<Device, CliError> {
    let checked = drivegen::check(description);
    if !checked.diagnostics.is_empty() {
        eprintln!("{}", checked.render());
    }
    checked
        .device
        .ok_or_else(|| CliError::Invalid(format!("{} has errors", description.display())))
}

/// The parameter called `name`, or an error suggesting the closest names.
pub fn parameter<'a>(device: &'a Device, name: &str) -> Result<&'a Parameter, CliError> {
    device
        .parameter(name)
        .ok_or_else(|| CliError::UnknownParameter {
            name: name.to_string(),
            closest: suggest::closest(name, device.parameters.iter().map(|p| p.name.as_str()))
                .into_iter()
                .map(str::to_string)
                .collect(),
        })
}

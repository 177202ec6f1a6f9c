//! `drivegen check`: validate a description.

use std::path::PathBuf;

use crate::error::CliError;

/// Arguments of `check`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
}

/// Prints a one-line summary of a valid description; diagnostics go to stderr.
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    println!(
        "{}: {} parameters, {} enums, {} flags types — ok",
        device.device.name,
        device.parameters.len(),
        device.enums.len(),
        device.flags.len()
    );
    Ok(())
}

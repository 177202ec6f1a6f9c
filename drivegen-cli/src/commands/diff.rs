//! `drivegen diff`: what changed between two descriptions (say, two firmware releases), and
//! whether code written against the old generated crate still compiles.

use std::path::PathBuf;

use drivegen::diff::{self, Impact};

use crate::error::CliError;

/// Arguments of `diff`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The old description (file, or a folder with a device.toml).
    old: PathBuf,
    /// The new description.
    new: PathBuf,
    /// Print the changes as JSON: `[{"impact": "breaking", "subject": ..., "what": ...}]`.
    #[arg(long)]
    json: bool,
}

/// Prints every change, grouped by impact; fails (exit code 1) if any change is breaking.
pub fn run(args: Args) -> Result<(), CliError> {
    let old = super::load(&args.old)?;
    let new = super::load(&args.new)?;
    let changes = diff::diff(&old, &new);
    if args.json {
        let json = serde_json::to_string_pretty(&changes).expect("changes serialize");
        println!("{json}");
    } else {
        print!("{}", diff::render(&changes));
    }
    match changes
        .iter()
        .filter(|c| c.impact == Impact::Breaking)
        .count()
    {
        0 => Ok(()),
        breaking => Err(CliError::Breaking(breaking)),
    }
}

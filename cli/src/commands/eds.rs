//! `drivegen eds export|import`: CiA 306 EDS files from descriptions, and overlay skeletons from
//! vendor EDS files.

use std::path::{Path, PathBuf};

use crate::error::CliError;

/// Arguments of `eds`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    action: Action,
}

#[derive(Debug, clap::Subcommand)]
enum Action {
    /// Write the CANopen objects of a description as an EDS file.
    Export {
        /// Description file, or a folder with a device.toml.
        description: PathBuf,
        /// Output file; must end in .eds for CANopen tools to accept it.
        #[arg(short, long)]
        out: PathBuf,
    },
    /// Write a TOML overlay skeleton for a vendor EDS (save it beside the EDS).
    Import {
        /// The vendor EDS or DCF file.
        eds: PathBuf,
        /// Output file; standard output if omitted.
        #[arg(short, long)]
        out: Option<PathBuf>,
    },
}

/// Runs `eds export` or `eds import`.
pub fn run(args: Args) -> Result<(), CliError> {
    match args.action {
        Action::Export { description, out } => export(&description, &out),
        Action::Import { eds, out } => import(&eds, out.as_deref()),
    }
}

fn export(description: &Path, out: &Path) -> Result<(), CliError> {
    let device = super::load(description)?;
    if !device.parameters.iter().any(|p| !p.canopen.is_empty()) {
        return Err(CliError::Usage(format!(
            "{} has no CANopen objects to export",
            description.display()
        )));
    }
    write(out, &drivegen::eds::export(&device))
}

fn import(eds: &Path, out: Option<&Path>) -> Result<(), CliError> {
    let overlay =
        drivegen::eds::import_overlay(eds).map_err(|e| CliError::Invalid(e.to_string()))?;
    match out {
        Some(path) => write(path, &overlay),
        None => {
            print!("{overlay}");
            Ok(())
        }
    }
}

fn write(path: &Path, text: &str) -> Result<(), CliError> {
    std::fs::write(path, text)
        .map_err(|e| CliError::Io(format!("cannot write {}: {e}", path.display())))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

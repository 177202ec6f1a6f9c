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
    super::write_file(out, &drivegen::eds::export(&device))
}

/// Writes the overlay skeleton (to `out`, else standard output), then prints the findings of its
/// check as saved (at `out`, else beside the EDS); fails when the overlay does not check.
fn import(eds: &Path, out: Option<&Path>) -> Result<(), CliError> {
    let saved_at = out.map_or_else(
        || drivegen::eds::default_overlay_path(eds),
        Path::to_path_buf,
    );
    let imported = drivegen::eds::import_overlay(eds, &saved_at)
        .map_err(|e| CliError::Invalid(e.to_string()))?;
    match out {
        Some(path) => super::write_file(path, &imported.overlay)?,
        None => print!("{}", imported.overlay),
    }
    let findings = imported.checked.render();
    if !findings.is_empty() {
        eprintln!("{findings}");
    }
    let (errors, warnings) = imported
        .checked
        .diagnostics
        .iter()
        .fold((0, 0), |(e, w), d| match d.severity {
            drivegen::Severity::Error => (e + 1, w),
            drivegen::Severity::Warning => (e, w + 1),
        });
    if imported.checks() {
        eprintln!(
            "the overlay checks as {} ({warnings} warnings)",
            saved_at.display()
        );
        Ok(())
    } else {
        Err(CliError::Invalid(format!(
            "the overlay does not check as {} ({errors} errors, {warnings} warnings): fix it (or the EDS) as the errors above say",
            saved_at.display()
        )))
    }
}

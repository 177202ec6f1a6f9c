//! `drivegen config`: a drive's configuration saved to a file (`pull`), written back (`push`)
//! and compared (`compare`, with a file or the live drive). The file format is
//! `drivegen::config_file` (docs/config-file.md).

mod clock;
mod compare;
mod live;
mod loaded;
mod pdo_mapping;
mod plan;
mod pull;
mod push;
mod selection;
mod unlock;

use std::path::PathBuf;

use crate::connect::BusArgs;
use crate::error::CliError;

/// Arguments of `config`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, clap::Subcommand)]
enum Command {
    /// Read every readable and writable parameter of a drive into a file: engineering value,
    /// raw value and unit, the identity read, the description, the time.
    Pull(PullArgs),
    /// Write a file's values back to a drive, in an order that works (unlocks, modes, bounds),
    /// each verified by reading it back, then stored; `--dry-run` prints the plan only.
    Push(PushArgs),
    /// The differences between a file and a drive, another file or the description's defaults
    /// (exit code 1 if any).
    #[command(visible_alias = "diff")]
    Compare(CompareArgs),
}

/// Arguments of `config pull`.
#[derive(Debug, clap::Args)]
pub struct PullArgs {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
    #[command(flatten)]
    bus: BusArgs,
    /// The file to write.
    #[arg(short, long, value_name = "FILE.toml")]
    output: PathBuf,
}

/// Arguments of `config push`.
#[derive(Debug, clap::Args)]
pub struct PushArgs {
    /// The file `config pull` wrote (values may be edited).
    file: PathBuf,
    #[command(flatten)]
    bus: BusArgs,
    /// Print what would be written, in order, and write nothing.
    #[arg(long)]
    dry_run: bool,
    /// The description to use instead of the one the file names.
    #[arg(long, value_name = "PATH")]
    description: Option<PathBuf>,
    /// The drive's password, for an unlock keyed by one (default: the password parameter's
    /// current value, where the drive lets it be read).
    #[arg(long)]
    password: Option<String>,
    /// Do not write the description's store command after the values.
    #[arg(long)]
    no_store: bool,
    /// Write although the drive's identity is not one the description covers (the identity the
    /// file holds must still match).
    #[arg(long)]
    no_identity_check: bool,
}

/// Arguments of `config compare`.
#[derive(Debug, clap::Args)]
pub struct CompareArgs {
    /// The file `config pull` wrote.
    file: PathBuf,
    /// A second file to compare with, instead of the live drive.
    other: Option<PathBuf>,
    /// Compare with the description's defaults instead of the live drive (parameters without
    /// one, or with a node-relative one, are left out).
    #[arg(long, conflicts_with = "other")]
    defaults: bool,
    #[command(flatten)]
    bus: BusArgs,
    /// The description to use instead of the one the file names.
    #[arg(long, value_name = "PATH")]
    description: Option<PathBuf>,
}

/// Runs the subcommand.
pub fn run(args: Args) -> Result<(), CliError> {
    match args.command {
        Command::Pull(args) => pull::run(args),
        Command::Push(args) => push::run(args),
        Command::Compare(args) => compare::run(args),
    }
}

//! `drivegen dbc export`: a description's PDOs as a DBC file for CAN log tools.

use std::path::PathBuf;

use crate::error::CliError;

/// Arguments of `dbc`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    action: Action,
}

#[derive(Debug, clap::Subcommand)]
enum Action {
    /// Write the description's PDOs as DBC messages: signals with scale, offset, unit, range and
    /// the value tables of enumerations.
    Export {
        /// Description file, or a folder with a device.toml.
        description: PathBuf,
        /// Node id the PDO identifiers are resolved for (default: the description's default
        /// node id).
        #[arg(long, value_parser = clap::value_parser!(u8).range(1..=127))]
        node_id: Option<u8>,
        /// Output file (.dbc).
        #[arg(short, long)]
        out: PathBuf,
    },
}

/// Runs `dbc export`.
pub fn run(args: Args) -> Result<(), CliError> {
    let Action::Export {
        description,
        node_id,
        out,
    } = args.action;
    let device = super::load(&description)?;
    let Some(node_id) = node_id.or(device.canopen.as_ref().map(|c| c.default_node_id)) else {
        return Err(CliError::Usage(format!(
            "{} speaks no CANopen: it has no PDOs to export",
            description.display()
        )));
    };
    if device.pdos().next().is_none() {
        return Err(CliError::Usage(format!(
            "{} declares no PDO ([[pdo]])",
            description.display()
        )));
    }
    let dbc = drivegen::dbc::export(&device, node_id);
    for skipped in &dbc.skipped {
        eprintln!("left out: {skipped}");
    }
    super::write_file(&out, &dbc.text)
}

//! `drivegen dump`: the normalized device model.

use std::path::PathBuf;

use drivegen::ir::Parameter;

use crate::error::CliError;
use crate::table;

/// Arguments of `dump`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
    /// Print the IR JSON (the schema of docs/ir-json.md).
    #[arg(long)]
    json: bool,
}

/// Prints the IR as JSON, or a table of parameters with type, unit and addresses.
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    if args.json {
        let json = serde_json::to_string_pretty(&device)
            .map_err(|e| CliError::Io(format!("cannot serialize the IR: {e}")))?;
        println!("{json}");
        return Ok(());
    }
    if let Some(identity) = &device.identity {
        println!("{identity}");
    }
    let mut rows = vec![vec![
        "parameter".to_string(),
        "type".to_string(),
        "unit".to_string(),
        "modbus".to_string(),
        "canopen".to_string(),
    ]];
    rows.extend(device.parameters.iter().map(row));
    print!("{}", table::render(&rows));
    Ok(())
}

fn row(p: &Parameter) -> Vec<String> {
    let access = |read: bool, write: bool| match (read, write) {
        (true, true) => "rw",
        (true, false) => "r",
        (false, true) => "w",
        (false, false) => "-",
    };
    let modbus: Vec<String> = p
        .modbus
        .iter()
        .map(|a| {
            let table = match a.table {
                drivegen::ir::Table::Input => "in",
                drivegen::ir::Table::Holding => "hold",
            };
            format!(
                "{table} {:#06x} {}",
                a.address,
                access(a.access.read, a.access.write)
            )
        })
        .collect();
    let canopen: Vec<String> = p
        .canopen
        .iter()
        .map(|a| {
            format!(
                "{:04X}:{:02X} {}",
                a.index,
                a.subindex,
                access(a.access.read, a.access.write)
            )
        })
        .collect();
    vec![
        p.name.clone(),
        p.data_type.name().to_owned(),
        p.unit.clone().unwrap_or_default(),
        modbus.join(", "),
        canopen.join(", "),
    ]
}

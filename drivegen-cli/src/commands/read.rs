//! `drivegen read`: parameters by name, in engineering units.

use std::path::PathBuf;

use drivegen::ir::{Device, Parameter};

use crate::codec;
use crate::connect::{BusArgs, Session};
use crate::drives::{self, Drives};
use crate::error::CliError;
use crate::table;

/// Arguments of `read`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
    /// Parameter names.
    #[arg(required = true)]
    parameters: Vec<String>,
    #[command(flatten)]
    bus: BusArgs,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// Reads each parameter once and prints a table (or JSON): of one drive, or with a column per
/// drive when several are named.
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    let parameters = resolve(&device, &args.parameters)?;
    let mut drives = Drives::open(&args.bus, &device)?;
    let Some(session) = drives.single() else {
        return run_each(&args, &device, &parameters, &mut drives);
    };
    let values = read_all(session, &device, &parameters)?;
    if args.json {
        let json: Vec<serde_json::Value> = parameters
            .iter()
            .zip(&values)
            .map(|(p, shown)| to_json(p, shown))
            .collect();
        println!("{}", serde_json::Value::from(json));
    } else {
        let mut rows = vec![vec!["parameter".into(), "value".into(), "raw".into()]];
        rows.extend(parameters.iter().zip(&values).map(|(p, s)| {
            vec![
                p.name.clone(),
                s.text.clone(),
                codec::raw_json(&s.raw).to_string(),
            ]
        }));
        print!("{}", table::render(&rows));
    }
    Ok(())
}

/// Reads each parameter from every drive and prints one table with a column per drive (or a
/// JSON array with an object per drive); fails when any drive did.
fn run_each(
    args: &Args,
    device: &Device,
    parameters: &[&Parameter],
    drives: &mut Drives<'_>,
) -> Result<(), CliError> {
    let outcomes = drives.read_each(device, parameters);
    if args.json {
        let values = |shown: &[drivebus::interpret::Shown]| -> serde_json::Value {
            parameters
                .iter()
                .zip(shown)
                .map(|(p, s)| to_json(p, s))
                .collect()
        };
        println!("{}", drives.to_json(&outcomes, values));
    } else {
        let header = std::iter::once("parameter".to_owned()).chain(drives.headers());
        let mut rows = vec![header.collect()];
        rows.extend(drives::rows(parameters, &outcomes));
        print!("{}", table::render(&rows));
    }
    match drives::failures(&outcomes) {
        0 => Ok(()),
        failed => Err(CliError::DrivesFailed {
            failed,
            asked: drives.len(),
        }),
    }
}

/// The parameters named, each checked to exist before anything is sent.
pub fn resolve<'a>(device: &'a Device, names: &[String]) -> Result<Vec<&'a Parameter>, CliError> {
    names.iter().map(|n| super::parameter(device, n)).collect()
}

/// Reads and decodes every parameter.
pub fn read_all(
    session: &mut Session,
    device: &Device,
    parameters: &[&Parameter],
) -> Result<Vec<drivebus::interpret::Shown>, CliError> {
    let values = session.read_many(parameters)?;
    Ok(parameters
        .iter()
        .zip(&values)
        .map(|(p, raw)| drivebus::interpret::show(device, p, raw))
        .collect())
}

/// One value as a JSON object.
pub fn to_json(parameter: &Parameter, shown: &drivebus::interpret::Shown) -> serde_json::Value {
    serde_json::json!({
        "parameter": parameter.name,
        "value": codec::value_json(&shown.value),
        "unit": parameter.unit,
        "raw": codec::raw_json(&shown.raw),
        "text": shown.text,
    })
}

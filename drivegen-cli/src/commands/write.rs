//! `drivegen write`: one parameter by name, value in engineering units.

use std::path::PathBuf;

use drivebus::interpret::Shown;
use drivegen::ir::{Device, Parameter};

use crate::codec;
use crate::connect::{BusArgs, Session};
use crate::error::CliError;

/// Arguments of `write`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
    /// Parameter name.
    parameter: String,
    /// Value: `1500rpm`, `49.5V`, an enum value name, flag names joined by `|`, or `raw:N` / `0x..`.
    #[arg(allow_hyphen_values = true)]
    value: String,
    #[command(flatten)]
    bus: BusArgs,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write without first checking the drive's identity against the description's `[identity]`.
    #[arg(long)]
    no_identity_check: bool,
}

/// Checks the value against the description, then writes it.
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    let parameter = super::parameter(&device, &args.parameter)?;
    let bytes = parse_value(&device, parameter, &args.value)?;
    let mut session = Session::open(&args.bus, &device)?;
    let shown = write_checked(
        &mut session,
        &device,
        parameter,
        &bytes,
        !args.no_identity_check,
    )?;
    if args.json {
        println!("{}", super::read::to_json(parameter, &shown));
    } else {
        println!(
            "{} = {} (raw {}) written to {}{}",
            parameter.name,
            shown.text,
            codec::raw_json(&shown.raw),
            session.target(),
            session.variant_note()
        );
    }
    Ok(())
}

/// `text` as the bytes of `parameter`, checked against its description (type, range, enum and
/// flag names, unit) before anything is sent.
pub fn parse_value(
    device: &Device,
    parameter: &Parameter,
    text: &str,
) -> Result<Vec<u8>, CliError> {
    drivebus::interpret::parse(device, parameter, text).map_err(|cause| CliError::Value {
        parameter: parameter.name.clone(),
        cause,
        cited: parameter.source.as_ref().and_then(|c| {
            let line = c.line?;
            Some(format!("{} line {line}", c.cited.file))
        }),
    })
}

/// Writes `bytes` (from [`parse_value`]) the way `drivegen write` does: the drive's identity
/// checked first when `check_identity` (a stop goes out whatever it reads), then the bounds set
/// by other parameters, the variant and the lock rules. Returns the value written.
pub fn write_checked(
    session: &mut Session,
    device: &Device,
    parameter: &Parameter,
    bytes: &[u8],
    check_identity: bool,
) -> Result<Shown, CliError> {
    if check_identity {
        // A stop goes out whatever the identity reads; the drive's answer is reported.
        let mismatch = crate::identity_check::verify(session, device).err();
        if let Some(refusal) = drivebus::interpret::waive_for_stop(parameter, bytes, mismatch) {
            return Err(refusal);
        }
    }
    session.write(device, parameter, bytes)?;
    Ok(drivebus::interpret::show(device, parameter, bytes))
}

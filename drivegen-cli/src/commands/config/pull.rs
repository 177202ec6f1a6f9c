//! `drivegen config pull`: every configuration parameter of a live drive into a file.

use std::path::Path;

use drivebus::interpret::{self, Raw, RawValue};
use drivegen::config_file::{
    self, ConfigFile, DescriptionRef, DriveRecord, IdentityEntry, SavedParameter, SavedRaw, Unread,
};
use drivegen::ir::{Device, Parameter};

use super::{clock, live, selection, PullArgs};
use crate::connect::Session;
use crate::error::CliError;

/// Reads the drive and writes the file; says how many were saved and how many not.
pub fn run(args: PullArgs) -> Result<(), CliError> {
    let device = crate::commands::load(&args.description)?;
    let mut session = Session::open(&args.bus, &device)?;
    let file = pull(&mut session, &device, &args.description)?;
    let text = config_file::render(&file);
    std::fs::write(&args.output, text)
        .map_err(|e| CliError::Io(format!("cannot write {}: {e}", args.output.display())))?;
    println!(
        "{} parameter(s) saved to {}, {} not read (listed under [unread]), from {}{}",
        file.parameters.len(),
        args.output.display(),
        file.unread.len(),
        session.target(),
        session.variant_note()
    );
    Ok(())
}

/// The drive's configuration as a file: each configuration parameter read, or listed unread
/// with the reason.
pub fn pull(
    session: &mut Session,
    device: &Device,
    description: &Path,
) -> Result<ConfigFile, CliError> {
    let identity = read_identity(session, device);
    let (parameters, unread) = read_configuration(session, device);
    Ok(ConfigFile {
        description: DescriptionRef {
            name: device.device.name.clone(),
            firmware: device.device.firmware.clone(),
            path: Some(absolute(description)),
        },
        drive: DriveRecord {
            target: session.target().to_owned(),
            variant: session.variant().selected().map(str::to_owned),
            pulled_at: clock::now_utc(),
        },
        identity,
        parameters,
        unread,
    })
}

/// The configuration parameters read, and those not read with the reason.
pub fn read_configuration(
    session: &mut Session,
    device: &Device,
) -> (Vec<SavedParameter>, Vec<Unread>) {
    let candidates = selection::configuration(device);
    let (reachable, unreachable): (Vec<&Parameter>, Vec<&Parameter>) = candidates
        .into_iter()
        .partition(|p| session.can_read(p) && session.can_write(p));
    let mut unread: Vec<Unread> = unreachable
        .iter()
        .map(|p| Unread {
            name: p.name.clone(),
            reason: format!("not both readable and writable over {}", session.protocol()),
            line: 0,
        })
        .collect();
    let mut saved = Vec::new();
    for (parameter, read) in reachable.iter().zip(live::read_each(session, &reachable)) {
        match read {
            Ok(bytes) => saved.push(saved_parameter(device, parameter, &bytes)),
            Err(reason) => unread.push(Unread {
                name: parameter.name.clone(),
                reason,
                line: 0,
            }),
        }
    }
    // In the description's order, so a file reads like the description.
    let position = |name: &str| device.parameters.iter().position(|p| p.name == name);
    unread.sort_by_key(|u| position(&u.name));
    (saved, unread)
}

/// One value as the file keeps it.
pub fn saved_parameter(device: &Device, parameter: &Parameter, bytes: &[u8]) -> SavedParameter {
    let shown = interpret::show(device, parameter, bytes);
    let raw = match shown.raw {
        Raw::Bytes(bytes) => SavedRaw::Bytes(bytes),
        Raw::Number(RawValue::Int(int)) => SavedRaw::Int(int),
        Raw::Number(RawValue::Float(float)) => SavedRaw::Float(float),
        Raw::Undecodable => SavedRaw::Bytes(bytes.to_vec()),
    };
    SavedParameter {
        name: parameter.name.clone(),
        value: shown.text,
        raw,
        unit: parameter.unit.clone(),
        line: 0,
    }
}

/// The identity parameters the bus reaches, read raw; one that cannot be read is left out
/// (and said so), as `drivegen write`'s check leaves it unchecked.
fn read_identity(session: &mut Session, device: &Device) -> Vec<IdentityEntry> {
    let mut checks = device.identity_checks();
    checks.retain(|c| session.can_read(c.parameter));
    let parameters: Vec<&Parameter> = checks.iter().map(|c| c.parameter).collect();
    let mut entries = Vec::new();
    for (parameter, read) in parameters.iter().zip(live::read_each(session, &parameters)) {
        let value = read
            .ok()
            .and_then(|bytes| interpret::raw::to_int(parameter.data_type, &bytes));
        match value {
            Some(raw) => entries.push(IdentityEntry {
                name: parameter.name.clone(),
                raw,
                line: 0,
            }),
            None => eprintln!(
                "warning: identity parameter {} could not be read; the file does not hold it",
                parameter.name
            ),
        }
    }
    entries
}

/// The description's path made absolute, so `push` finds it from anywhere.
fn absolute(path: &Path) -> String {
    std::fs::canonicalize(path)
        .unwrap_or_else(|_| path.to_path_buf())
        .display()
        .to_string()
}

//! `drivegen config compare`: a file against the live drive, or against a second file; a table
//! of the values that differ, in engineering units, and an exit code that says whether any do.

use drivebus::interpret;
use drivegen::ir::{DataType, Device, Number, Parameter};

use super::loaded::{Desired, Loaded};
use super::push::same;
use super::{live, CompareArgs};
use crate::connect::Session;
use crate::error::CliError;
use crate::table;

/// One difference: what, the left side, the right side.
type Row = [String; 3];

/// Prints the differences; fails with [`CliError::Differs`] when there are any.
pub fn run(args: CompareArgs) -> Result<(), CliError> {
    let loaded = Loaded::open(&args.file, args.description.as_deref())?;
    let left = loaded.desired()?;
    let (right_name, rows) = match &args.other {
        None if args.defaults => (
            "description default".to_owned(),
            with_defaults(&loaded.device, &left),
        ),
        Some(other) => {
            let path = args
                .description
                .clone()
                .or_else(|| loaded.file.description.path.clone().map(Into::into));
            let second = Loaded::open(other, path.as_deref())?;
            if second.device.device.name != loaded.device.device.name {
                return Err(second.refuse(
                    None,
                    format!(
                        "read from a {} drive, {} from a {} drive: nothing to compare",
                        second.file.description.name, loaded.path, loaded.file.description.name
                    ),
                ));
            }
            let right = second.desired()?;
            (
                second.path.clone(),
                with_file(&loaded.device, &left, &right),
            )
        }
        None => {
            let mut session = Session::open(&args.bus, &loaded.device)?;
            let mut rows = identity_rows(&loaded, &mut session);
            rows.extend(with_drive(&loaded.device, &mut session, &left));
            (session.target().to_owned(), rows)
        }
    };
    if rows.is_empty() {
        println!("no differences between {} and {right_name}", loaded.path);
        return Ok(());
    }
    let mut table_rows = vec![vec!["parameter".into(), loaded.path.clone(), right_name]];
    table_rows.extend(rows.iter().map(|r| r.to_vec()));
    print!("{}", table::render(&table_rows));
    Err(CliError::Differs(rows.len()))
}

fn shown(device: &Device, parameter: &Parameter, bytes: &[u8]) -> String {
    interpret::show(device, parameter, bytes).text
}

/// Two files' values; a parameter only one holds is a difference too.
fn with_file(device: &Device, left: &[Desired<'_>], right: &[Desired<'_>]) -> Vec<Row> {
    let mut rows = Vec::new();
    for l in left {
        let r = right.iter().find(|r| r.parameter.name == l.parameter.name);
        match r {
            Some(r) if same(l.parameter, &l.bytes, &r.bytes) => {}
            Some(r) => rows.push([
                l.parameter.name.clone(),
                shown(device, l.parameter, &l.bytes),
                shown(device, r.parameter, &r.bytes),
            ]),
            None => rows.push([
                l.parameter.name.clone(),
                shown(device, l.parameter, &l.bytes),
                "(not in the file)".into(),
            ]),
        }
    }
    for r in right {
        if !left.iter().any(|l| l.parameter.name == r.parameter.name) {
            rows.push([
                r.parameter.name.clone(),
                "(not in the file)".into(),
                shown(device, r.parameter, &r.bytes),
            ]);
        }
    }
    rows
}

/// The file's values against the description's defaults, where it gives one for any node.
fn with_defaults(device: &Device, left: &[Desired<'_>]) -> Vec<Row> {
    left.iter()
        .filter_map(|d| {
            let default = default_bytes(d.parameter)?;
            (!same(d.parameter, &d.bytes, &default)).then(|| {
                [
                    d.parameter.name.clone(),
                    shown(device, d.parameter, &d.bytes),
                    shown(device, d.parameter, &default),
                ]
            })
        })
        .collect()
}

/// The raw bytes of a parameter's default; none for a node-relative one.
fn default_bytes(parameter: &Parameter) -> Option<Vec<u8>> {
    if parameter.default_plus_node_id {
        return None;
    }
    let data_type = parameter.data_type;
    Some(match (parameter.default?, data_type) {
        (Number::Int(int), _) => interpret::raw::from_int(data_type, i128::from(int)),
        (Number::Float(float), DataType::F32) => (float as f32).to_le_bytes().to_vec(),
        (Number::Float(float), DataType::F64) => float.to_le_bytes().to_vec(),
        (Number::Float(_), _) => return None,
    })
}

/// The file's values against the drive's; one the drive does not give is a difference.
fn with_drive(device: &Device, session: &mut Session, left: &[Desired<'_>]) -> Vec<Row> {
    let parameters: Vec<&Parameter> = left.iter().map(|d| d.parameter).collect();
    let reads = live::read_each(session, &parameters);
    left.iter()
        .zip(reads)
        .filter_map(|(d, read)| {
            let drive = match read {
                Ok(bytes) if same(d.parameter, &bytes, &d.bytes) => return None,
                Ok(bytes) => shown(device, d.parameter, &bytes),
                Err(why) => format!("(not read: {why})"),
            };
            Some([
                d.parameter.name.clone(),
                shown(device, d.parameter, &d.bytes),
                drive,
            ])
        })
        .collect()
}

/// The identity values the file holds that the drive does not read the same.
fn identity_rows(loaded: &Loaded, session: &mut Session) -> Vec<Row> {
    loaded
        .file
        .identity
        .iter()
        .filter_map(|entry| {
            let parameter = loaded.device.parameter(&entry.name)?;
            let found = live::read_one(session, parameter)
                .ok()
                .and_then(|bytes| interpret::raw::to_int(parameter.data_type, &bytes));
            (found != Some(entry.raw)).then(|| {
                [
                    format!("identity {}", entry.name),
                    entry.raw.to_string(),
                    found.map_or("(not read)".into(), |v| v.to_string()),
                ]
            })
        })
        .collect()
}

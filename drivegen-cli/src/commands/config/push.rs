//! `drivegen config push`: a file's values written back to a drive. Everything in the file is
//! checked before the bus is opened; the drive's identity and variant are checked against the
//! file before anything is written; only values that differ are written, in the order
//! [`plan::order`] gives, between the unlocks and the lock the description declares; each is
//! read back; every parameter is reported written, unchanged or refused with the reason.

use drivebus::interpret;
use drivegen::ir::{CommandKind, Device, Effect, Parameter};

use super::loaded::{Desired, Loaded};
use super::plan::{self, Change};
use super::unlock::{self, Step};
use super::{live, pdo_mapping, PushArgs};
use crate::connect::Session;
use crate::error::CliError;
use crate::table;

/// What became of one parameter.
enum Outcome {
    Written,
    /// Written to a parameter that takes effect after a reset, which still reads back this.
    WrittenPending(String),
    Unchanged,
    Refused(String),
}

/// What a push writes, in order: the grants, the values, the lock, the store commands.
struct Plan<'d> {
    grants: Vec<Step<'d>>,
    changes: Vec<Change<'d>>,
    relock: Option<Step<'d>>,
    stores: Vec<Step<'d>>,
}

/// Checks the file, then the drive, then writes (or prints the plan).
pub fn run(args: PushArgs) -> Result<(), CliError> {
    let loaded = Loaded::open(&args.file, args.description.as_deref())?;
    let desired = loaded.desired()?;
    let device = &loaded.device;
    let mut session = Session::open(&args.bus, device)?;
    check_drive(&loaded, &mut session, args.no_identity_check)?;
    let (changes, outcomes) = compare_with_drive(&mut session, &desired);
    refuse_invalid(&loaded, &changes)?;
    let changes = pdo_mapping::sequence(plan::order(device, changes), &desired);
    let changed: Vec<&Parameter> = changes.iter().map(|c| c.parameter).collect();
    let grants = unlock::unlocks(device, &mut session, &changed, args.password.as_deref())?;
    let plan = Plan {
        relock: (!grants.is_empty())
            .then(|| unlock::relock(device))
            .flatten(),
        stores: match args.no_store || changes.is_empty() {
            true => Vec::new(),
            false => store_steps(device, &session),
        },
        grants,
        changes,
    };
    if args.dry_run {
        print_plan(device, &plan);
        return Ok(());
    }
    execute(&loaded, &mut session, &plan, outcomes)
}

/// Writes the plan, reports each parameter, and fails if any was refused.
fn execute(
    loaded: &Loaded,
    session: &mut Session,
    plan: &Plan<'_>,
    mut outcomes: Outcomes,
) -> Result<(), CliError> {
    let device = &loaded.device;
    // The report follows the push: what needed no write (by line), then each write in turn.
    outcomes.sort_by_key(|(_, line, _)| *line);
    let mut log: Vec<Row> = outcomes.iter().map(row).collect();
    let mut refused = outcomes
        .iter()
        .filter(|(_, _, o)| matches!(o, Outcome::Refused(_)))
        .count();
    let unlocked = write_steps(device, session, &plan.grants, &mut log);
    for change in &plan.changes {
        let outcome = match unlocked {
            true => write_verified(device, session, change),
            false => Outcome::Refused("not written: the unlock before it failed".into()),
        };
        refused += usize::from(matches!(outcome, Outcome::Refused(_)));
        let entry = (change.parameter.name.clone(), change.line, outcome);
        let mut logged = row(&entry);
        if matches!(entry.2, Outcome::Written | Outcome::WrittenPending(_)) {
            logged[2].push_str(takes_effect(change.parameter));
        }
        log.push(logged);
        outcomes.push(entry);
    }
    // The lock goes out whatever happened before it: a push never leaves a drive unlocked.
    write_steps(device, session, plan.relock.as_slice(), &mut log);
    if refused == 0 {
        write_steps(device, session, &plan.stores, &mut log);
    }
    report(&loaded.path, &outcomes, &log, session.target());
    match refused {
        0 => Ok(()),
        refused => Err(CliError::PushIncomplete {
            refused,
            planned: plan.changes.len().max(refused),
        }),
    }
}

/// Refuses, before anything is written, a value the description does not allow that a drive
/// held when the file was read and that would now be written.
fn refuse_invalid(loaded: &Loaded, changes: &[Change<'_>]) -> Result<(), CliError> {
    match changes.iter().find_map(|c| Some((c, c.invalid.as_ref()?))) {
        Some((change, why)) => Err(loaded.refuse(
            Some(change.line),
            format!(
                "{}: {why} (the drive held it when the file was read; edit the value)",
                change.parameter.name
            ),
        )),
        None => Ok(()),
    }
}

/// The drive is the one the file was read from: the description covers its identity (unless
/// `--no-identity-check`), each identity value the file holds reads the same, and it is in the
/// file's variant.
pub fn check_drive(
    loaded: &Loaded,
    session: &mut Session,
    no_identity_check: bool,
) -> Result<(), CliError> {
    let device = &loaded.device;
    if !no_identity_check {
        crate::identity_check::verify(session, device)?;
    }
    for entry in &loaded.file.identity {
        let parameter = device.parameter(&entry.name).ok_or_else(|| {
            loaded.refuse(
                Some(entry.line),
                format!(
                    "identity `{}` is not a parameter of the description",
                    entry.name
                ),
            )
        })?;
        let read = live::read_one(session, parameter)?;
        let found = interpret::raw::to_int(parameter.data_type, &read);
        if found != Some(entry.raw) {
            return Err(CliError::ForeignDrive(format!(
                "{}:{}: {} was {} when the file was read, {} reads {}",
                loaded.path,
                entry.line,
                entry.name,
                entry.raw,
                session.target(),
                found.map_or("nothing".into(), |v| v.to_string())
            )));
        }
    }
    let file_variant = loaded.file.drive.variant.as_deref();
    let drive_variant = session.variant().selected();
    if file_variant.is_some() && file_variant != drive_variant {
        return Err(CliError::ForeignDrive(format!(
            "{}: the file was read from variant {}, the drive is in {}",
            loaded.path,
            file_variant.unwrap_or_default(),
            drive_variant.unwrap_or("an unknown variant")
        )));
    }
    Ok(())
}

type Outcomes = Vec<(String, u32, Outcome)>;

/// The values that differ from the drive's, and the outcome of those that need no write.
fn compare_with_drive<'d>(
    session: &mut Session,
    desired: &[Desired<'d>],
) -> (Vec<Change<'d>>, Outcomes) {
    let mut outcomes = Vec::new();
    let (reachable, unreachable): (Vec<&Desired<'d>>, Vec<&Desired<'d>>) = desired
        .iter()
        .partition(|d| session.can_read(d.parameter) && session.can_write(d.parameter));
    for d in unreachable {
        let why = format!("not both readable and writable over {}", session.protocol());
        outcomes.push((d.parameter.name.clone(), d.line, Outcome::Refused(why)));
    }
    let parameters: Vec<&Parameter> = reachable.iter().map(|d| d.parameter).collect();
    let mut changes = Vec::new();
    for (d, read) in reachable
        .into_iter()
        .zip(live::read_each(session, &parameters))
    {
        match read {
            Ok(current) if same(d.parameter, &current, &d.bytes) => {
                outcomes.push((d.parameter.name.clone(), d.line, Outcome::Unchanged));
            }
            Ok(current) => changes.push(Change {
                parameter: d.parameter,
                current,
                wanted: d.bytes.clone(),
                line: d.line,
                invalid: d.invalid.clone(),
            }),
            Err(why) => outcomes.push((
                d.parameter.name.clone(),
                d.line,
                Outcome::Refused(format!("cannot be read: {why}")),
            )),
        }
    }
    (changes, outcomes)
}

/// Whether two raw values of `parameter` are the same value (an integer whatever its width on
/// the wire, a string without its padding).
pub fn same(parameter: &Parameter, a: &[u8], b: &[u8]) -> bool {
    match (
        interpret::raw::to_int(parameter.data_type, a),
        interpret::raw::to_int(parameter.data_type, b),
    ) {
        (Some(a), Some(b)) => a == b,
        _ => a
            .iter()
            .rev()
            .skip_while(|b| **b == 0)
            .eq(b.iter().rev().skip_while(|b| **b == 0)),
    }
}

/// Writes one value and reads it back.
fn write_verified(device: &Device, session: &mut Session, change: &Change<'_>) -> Outcome {
    if let Err(e) = session.write(device, change.parameter, &change.wanted) {
        return Outcome::Refused(e.to_string());
    }
    match live::read_one(session, change.parameter) {
        Ok(back) if same(change.parameter, &back, &change.wanted) => Outcome::Written,
        // Such a drive may answer the old value until it restarts.
        Ok(back) if change.parameter.effect != Effect::Immediate => {
            Outcome::WrittenPending(interpret::show(device, change.parameter, &back).text)
        }
        Ok(back) => Outcome::Refused(format!(
            "written, but reads back {}",
            interpret::show(device, change.parameter, &back).text
        )),
        Err(e) => Outcome::Refused(format!("written, but not read back: {e}")),
    }
}

/// Writes grants, the lock or the store commands; records each; whether all went through.
fn write_steps(
    device: &Device,
    session: &mut Session,
    steps: &[Step<'_>],
    log: &mut Vec<Row>,
) -> bool {
    let mut all = true;
    for step in steps {
        let result = session.write(device, step.parameter, &step.bytes);
        all &= result.is_ok();
        log.push([
            format!("{} ({})", step.what, step.parameter.name),
            String::new(),
            result.map_or_else(|e| format!("refused: {e}"), |()| "written".into()),
        ]);
    }
    all
}

/// The store commands the description declares that this bus reaches.
fn store_steps<'d>(device: &'d Device, session: &Session) -> Vec<Step<'d>> {
    device
        .parameters
        .iter()
        .filter(|p| session.can_write(p))
        .filter_map(|p| {
            let store = p
                .command
                .as_ref()?
                .values()
                .find(|c| c.kind == CommandKind::Store)?;
            Some(Step {
                what: "store".into(),
                parameter: p,
                bytes: interpret::raw::from_int(p.data_type, i128::from(store.value?)),
                secret: false,
            })
        })
        .collect()
}

fn print_plan(device: &Device, plan: &Plan<'_>) {
    let mut rows = vec![vec![
        "step".into(),
        "parameter".into(),
        "drive now".into(),
        "file".into(),
    ]];
    let step_row = |step: &Step<'_>| {
        vec![
            step.what.clone(),
            step.parameter.name.clone(),
            String::new(),
            match step.secret {
                true => "(the password)".into(),
                false => format!(
                    "raw {}",
                    interpret::raw::to_int(step.parameter.data_type, &step.bytes)
                        .unwrap_or_default()
                ),
            },
        ]
    };
    rows.extend(plan.grants.iter().map(step_row));
    rows.extend(plan.changes.iter().map(|c| {
        vec![
            "write".into(),
            c.parameter.name.clone(),
            match c.current.is_empty() {
                true => String::new(),
                false => interpret::show(device, c.parameter, &c.current).text,
            },
            interpret::show(device, c.parameter, &c.wanted).text,
        ]
    }));
    rows.extend(plan.relock.iter().map(step_row));
    rows.extend(plan.stores.iter().map(step_row));
    print!("{}", table::render(&rows));
    println!(
        "dry run: {} value(s) to write, nothing written",
        plan.changes.len()
    );
}

/// When a written value takes effect, where that is not at once.
fn takes_effect(parameter: &Parameter) -> &'static str {
    match parameter.effect {
        Effect::Immediate => "",
        Effect::AfterReset => " (takes effect after a reset)",
        Effect::AfterStoreReset => " (takes effect after the store and a reset)",
    }
}

/// A line of the report: parameter (or step), file line, outcome.
type Row = [String; 3];

fn row((name, line, outcome): &(String, u32, Outcome)) -> Row {
    let text = match outcome {
        Outcome::Written => "written".to_owned(),
        Outcome::WrittenPending(reads) => format!("written, reads {reads} meanwhile"),
        Outcome::Unchanged => "unchanged".to_owned(),
        Outcome::Refused(why) => format!("refused: {why}"),
    };
    [name.clone(), line.to_string(), text]
}

fn report(file: &str, outcomes: &Outcomes, log: &[Row], target: &str) {
    let mut rows = vec![vec!["parameter".into(), "line".into(), "outcome".into()]];
    rows.extend(log.iter().map(|r| r.to_vec()));
    print!("{}", table::render(&rows));
    let count = |f: fn(&Outcome) -> bool| outcomes.iter().filter(|(_, _, o)| f(o)).count();
    println!(
        "{file} → {target}: {} written, {} unchanged, {} refused",
        count(|o| matches!(o, Outcome::Written | Outcome::WrittenPending(_))),
        count(|o| matches!(o, Outcome::Unchanged)),
        count(|o| matches!(o, Outcome::Refused(_)))
    );
}

//! Several drives on one bus, for `read` and `watch` with a repeated `--unit` or `--node-id`:
//! a session each on one connection (CANopen nodes through the network manager, read at once;
//! Modbus units one after the other), shown as one table with a column per drive. A drive that
//! fails shows its error in its column; the others still show.

use drivebus::interpret::Shown;
use drivegen::ir::{Device, Parameter};

use crate::commands::read;
use crate::connect::{BusArgs, Session};
use crate::error::CliError;

/// What one drive gave: its values, in the order of the parameters, or why it gave none.
pub type Outcome = Result<Vec<Shown>, CliError>;

/// The drives the options name, on the one bus they name.
pub struct Drives<'d> {
    sessions: Vec<Session<'d>>,
}

impl<'d> Drives<'d> {
    /// Opens the bus once and a session for each drive named (see [`Session::open_each`]).
    pub fn open(args: &BusArgs, device: &'d Device) -> Result<Self, CliError> {
        Ok(Self {
            sessions: Session::open_each(args, device)?,
        })
    }

    /// Opens them on one SDO client with the CAN bus at hand (see
    /// [`Session::open_each_on_one_client`]).
    pub fn open_on_one_client(args: &BusArgs, device: &'d Device) -> Result<Self, CliError> {
        Ok(Self {
            sessions: Session::open_each_on_one_client(args, device)?,
        })
    }

    /// The one drive, when only one was named: it keeps the one-drive output.
    pub fn single(&mut self) -> Option<&mut Session<'d>> {
        match self.sessions.as_mut_slice() {
            [session] => Some(session),
            _ => None,
        }
    }

    /// The sessions, one a drive, in order.
    pub fn sessions(&self) -> &[Session<'d>] {
        &self.sessions
    }

    /// Each drive: `("unit", 3)`, `("node", 5)`.
    pub fn ids(&self) -> Vec<(&'static str, u8)> {
        self.sessions.iter().map(Session::drive).collect()
    }

    /// How many drives there are.
    pub fn len(&self) -> usize {
        self.sessions.len()
    }

    /// Each drive's column header: `unit 3`, `node 5`.
    pub fn headers(&self) -> Vec<String> {
        self.sessions
            .iter()
            .map(|s| {
                let (kind, id) = s.drive();
                format!("{kind} {id}")
            })
            .collect()
    }

    /// Reads `parameters` from every drive. CANopen nodes at once through the network manager
    /// that shares the CAN bus (a node that does not answer costs its own timeout, not the
    /// others'); Modbus units and RS-232 stations one after the other: one line carries one
    /// request at a time anyway.
    pub fn read_each(&mut self, device: &Device, parameters: &[&Parameter]) -> Vec<Outcome> {
        crate::connect::each(&mut self.sessions, |session| {
            read::read_all(session, device, parameters)
        })
    }

    /// Each drive's outcome as JSON: `{"unit": 3, "values": ...}` or `{"unit": 5, "error": ...}`,
    /// the values as `values` makes them.
    pub fn to_json(
        &self,
        outcomes: &[Outcome],
        values: impl Fn(&[Shown]) -> serde_json::Value,
    ) -> serde_json::Value {
        let drives = self
            .sessions
            .iter()
            .zip(outcomes)
            .map(|(session, outcome)| {
                let (kind, id) = session.drive();
                let mut object = serde_json::Map::new();
                object.insert(kind.into(), id.into());
                match outcome {
                    Ok(shown) => object.insert("values".into(), values(shown)),
                    Err(e) => object.insert("error".into(), e.to_string().into()),
                };
                serde_json::Value::Object(object)
            });
        drives.collect()
    }
}

/// The table's rows (without its header): a row per parameter, its name then a cell per drive.
/// A drive that failed shows its error in its first cell and `-` below.
pub fn rows(parameters: &[&Parameter], outcomes: &[Outcome]) -> Vec<Vec<String>> {
    parameters
        .iter()
        .enumerate()
        .map(|(row, parameter)| {
            let cells = outcomes.iter().map(|outcome| match outcome {
                Ok(shown) => shown
                    .get(row)
                    .map_or_else(|| "-".into(), |s| s.text.clone()),
                Err(e) if row == 0 => format!("error: {e}"),
                Err(_) => "-".into(),
            });
            std::iter::once(parameter.name.clone())
                .chain(cells)
                .collect()
        })
        .collect()
}

/// How many outcomes failed.
pub fn failures(outcomes: &[Outcome]) -> usize {
    outcomes.iter().filter(|o| o.is_err()).count()
}

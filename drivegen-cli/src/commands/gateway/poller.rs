//! The bus side: a thread per connection (a line's) that owns it, reads each of its drives'
//! parameters at the drive's own interval, and answers set requests between polls. It reports
//! each drive's newest state only (a `watch` channel each): a slow broker sees the latest
//! values, never a backlog.

use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, TryRecvError};
use std::time::{Duration, Instant, SystemTime};

use drivebus::interpret::Shown;
use drivegen::ir::Parameter;
use tokio::sync::{oneshot, watch};

use super::connection::Connection;
use super::exposed::Drive;
use super::payload;
use super::pdo::ByPdo;
use super::pdo_bus::PdoBus;
use super::refusal::{Refusal, Refused};
use crate::commands::{read, write};
use crate::connect::{self, Session};

/// What the drive gave at its last poll.
#[derive(Debug, Clone)]
pub enum Report {
    /// Not polled yet.
    Starting,
    /// Every parameter's value payload, by name, in the file's order.
    Values(Vec<(String, serde_json::Value)>),
    /// The bus or the drive failed; why.
    Failed(String),
}

/// A client's set message for one parameter, and where its result goes.
pub struct SetRequest {
    /// The parameter's name.
    pub parameter: String,
    /// The message as received (MQTT), or as an OPC UA write is put in those words.
    pub message: Vec<u8>,
    /// The result.
    pub reply: oneshot::Sender<SetReply>,
}

/// The answer to a set request.
pub struct SetReply {
    /// The result payload (MQTT's `.../set/result`).
    pub payload: serde_json::Value,
    /// Why it was refused, when it was (OPC UA answers with a status code of its kind).
    #[cfg_attr(not(feature = "opcua"), allow(dead_code))]
    pub refused: Option<Refusal>,
}

/// A drive a line's poller serves: its own interval, report channel and session.
pub struct Served<'d> {
    drive: &'d Drive,
    parameters: Vec<&'d Parameter>,
    reports: watch::Sender<Report>,
    session: Option<Session<'d>>,
    /// When its next poll is due.
    next: Instant,
    /// Whether its last poll failed.
    failed: bool,
    /// Its values by TPDO (`pdo = true`).
    pdo: Option<ByPdo<'d>>,
}

impl<'d> Served<'d> {
    /// `drive`, reporting on `reports`, due for a poll now. A CANopen node's node-relative
    /// defaults its description refuses are warned of here, once (not at each reconnection).
    pub fn new(drive: &'d Drive, reports: watch::Sender<Report>) -> Self {
        if drive.bus.can.is_some() {
            if let Ok(node) = connect::drive_id(&drive.bus, &drive.device) {
                connect::warn_node_relative_defaults(&drive.device, node);
            }
        }
        let parameters: Vec<&Parameter> = drive
            .parameters
            .iter()
            .filter_map(|name| drive.parameter(name))
            .collect();
        Self {
            pdo: drive.pdo.on().then(|| ByPdo::plan(drive, &parameters)),
            parameters,
            drive,
            reports,
            session: None,
            next: Instant::now(),
            failed: false,
        }
    }
}

/// A set request for the drive at this place in its line's poller.
pub type LineRequest = (usize, SetRequest);

/// Hands a drive's set requests to its line's poller, tagged with the drive's place there,
/// until either side is gone: a drive's requests keep the channel of their own (its MQTT task
/// holds the sender) while the poller waits on one channel for all its drives.
pub fn forward(slot: usize, pending: &Receiver<SetRequest>, line: &Sender<LineRequest>) {
    for request in pending {
        if line.send((slot, request)).is_err() {
            return;
        }
    }
}

/// Serves the drives of one line through `connection` until `stop` turns true or every set
/// requests' sender is gone: each drive is polled at its own interval, the one due first
/// first, and set requests are answered as soon as the poll under way ends, before any other
/// poll (a write never waits for a round of polls). On a CAN bus with drives by PDO, the bus's
/// SYNCs go out on their own schedule between the polls ([`PdoBus`]). When it returns, the
/// drives' TPDOs have been put back.
pub fn run<'d>(
    mut connection: Connection<'d>,
    mut served: Vec<Served<'d>>,
    requests: &Receiver<LineRequest>,
    stop: &watch::Receiver<bool>,
) {
    let mut pdo_bus = PdoBus::new(served.iter().map(|s| s.drive));
    while !*stop.borrow() {
        let Some(slot) = due_first(&served) else {
            return;
        };
        let sync = pdo_bus.as_ref().and_then(PdoBus::next_sync);
        // A SYNC due no later than the poll goes out first: the poll then takes its answer.
        let syncing = sync.is_some_and(|at| at <= served[slot].next);
        let due = match sync {
            Some(at) if syncing => at,
            _ => served[slot].next,
        };
        let wait = due.saturating_duration_since(Instant::now());
        let request = match wait.is_zero() {
            true => requests
                .try_recv()
                .map_err(|e| e == TryRecvError::Disconnected),
            false => requests
                .recv_timeout(wait)
                .map_err(|e| e == RecvTimeoutError::Disconnected),
        };
        match request {
            Ok((slot, request)) => {
                if let Some(drive) = served.get_mut(slot) {
                    answer(&mut connection, drive, request);
                }
            }
            Err(true) => return,
            Err(false) if wait.is_zero() && syncing => {
                if let Some(pdo_bus) = &mut pdo_bus {
                    sync_bus(&connection, pdo_bus);
                }
            }
            Err(false) if wait.is_zero() => {
                poll(&mut connection, &mut served, slot, pdo_bus.as_mut())
            }
            // Not due yet: the next turn polls it.
            Err(false) => {}
        }
    }
}

/// The drive whose poll is due first (the first in the file among equals).
fn due_first(served: &[Served<'_>]) -> Option<usize> {
    (0..served.len()).min_by_key(|&slot| served[slot].next)
}

/// Sends the bus's SYNC (skipped while the connection is closed). A bus that fails here fails
/// the next poll too, which reports it.
fn sync_bus(connection: &Connection<'_>, pdo_bus: &mut PdoBus) {
    if let Err(e) = pdo_bus.tick(connection.can().as_ref()) {
        tracing::debug!("SYNC: {e}");
    }
}

/// Polls the drive at `slot` and reports. A drive that fails is reached again at its next
/// poll; when every drive on the line has failed, the connection is opened again too.
fn poll<'d>(
    connection: &mut Connection<'d>,
    served: &mut [Served<'d>],
    slot: usize,
    pdo_bus: Option<&mut PdoBus>,
) {
    // The CAN identifiers the other drives' TPDOs go out on.
    let taken: Vec<u16> = (0..served.len())
        .filter(|&other| other != slot)
        .filter_map(|other| served[other].pdo.as_ref()?.can_id())
        .collect();
    let Some(drive) = served.get_mut(slot) else {
        return;
    };
    drive.next = Instant::now() + Duration::from_millis(drive.drive.interval_ms.into());
    let report = read(connection, drive, pdo_bus, &taken);
    drive.failed = matches!(report, Report::Failed(_));
    if drive.failed {
        drive.session = None;
        if let Some(pdo) = &mut drive.pdo {
            pdo.end();
        }
    }
    log_change(&drive.drive.name, &drive.reports.borrow(), &report);
    drive.reports.send_replace(report);
    if served.iter().all(|s| s.failed) {
        for drive in served.iter_mut() {
            drive.session = None;
        }
        connection.close();
    }
}

/// One poll of `drive`'s parameters.
fn read<'d>(
    connection: &mut Connection<'d>,
    served: &mut Served<'d>,
    pdo_bus: Option<&mut PdoBus>,
    taken: &[u16],
) -> Report {
    let drive = served.drive;
    let session = match connection.reach(drive, &mut served.session) {
        Ok(session) => session,
        Err(why) => return Report::Failed(why),
    };
    let values = match (&mut served.pdo, pdo_bus) {
        (Some(pdo), Some(pdo_bus)) => pdo.read(drive, session, &served.parameters, pdo_bus, taken),
        _ => read::read_all(session, &drive.device, &served.parameters),
    };
    match values {
        Ok(values) => {
            let time = SystemTime::now();
            let payloads = served
                .parameters
                .iter()
                .zip(&values)
                .map(|(p, shown)| (p.name.clone(), payload::value(p, shown, time)))
                .collect();
            Report::Values(payloads)
        }
        Err(e) => Report::Failed(e.to_string()),
    }
}

/// Writes a set request through `drivegen write`'s checks and sends the result payload.
fn answer<'d>(connection: &mut Connection<'d>, served: &mut Served<'d>, request: SetRequest) {
    let drive = served.drive;
    let parameter = drive.parameter(&request.parameter);
    let outcome = set(connection, served, parameter, &request.message);
    match &outcome {
        Ok(shown) => {
            tracing::info!(drive = %drive.name, parameter = %request.parameter, value = %shown.text, "written")
        }
        Err(refused) => {
            tracing::warn!(drive = %drive.name, parameter = %request.parameter, "write refused: {}", refused.why)
        }
    }
    let refused = outcome.as_ref().err().map(|r| r.kind);
    let reply = SetReply {
        payload: payload::set_result(parameter, &outcome.map_err(|r| r.why)),
        refused,
    };
    // The client may have gone; the write's outcome is logged either way.
    let _ = request.reply.send(reply);
}

fn set<'d>(
    connection: &mut Connection<'d>,
    served: &mut Served<'d>,
    parameter: Option<&Parameter>,
    message: &[u8],
) -> Result<Shown, Refused> {
    let drive = served.drive;
    let parameter =
        parameter.ok_or_else(|| Refused::new(Refusal::NotWritable, "no such parameter"))?;
    let text = payload::set_text(message).map_err(|why| Refused::new(Refusal::WrongType, why))?;
    let bytes = write::parse_value(&drive.device, parameter, &text).map_err(|e| Refused::of(&e))?;
    // A drive whose last poll failed is offline: nothing is sent to it until a poll reaches it.
    let offline = || {
        Refused::new(
            Refusal::Communication,
            "the drive is offline: nothing written",
        )
    };
    if served.failed || served.session.is_none() {
        return Err(offline());
    }
    let open = connection
        .reach(drive, &mut served.session)
        .map_err(|why| Refused::new(Refusal::Communication, why))?;
    write::write_checked(open, &drive.device, parameter, &bytes, true).map_err(|e| Refused::of(&e))
}

/// Logs when a drive starts or stops answering, not at every poll.
fn log_change(drive: &str, before: &Report, now: &Report) {
    match (before, now) {
        (Report::Failed(_), Report::Failed(_)) | (Report::Values(_), Report::Values(_)) => {}
        (_, Report::Failed(why)) => tracing::warn!(drive, "offline: {why}"),
        (_, Report::Values(_)) => tracing::info!(drive, "online"),
        (_, Report::Starting) => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_reach_the_line_tagged_with_their_drive_and_the_forwarder_ends_with_them() {
        let (requests, pending) = std::sync::mpsc::channel();
        let (line, forwarded) = std::sync::mpsc::channel();
        let forwarder = std::thread::spawn(move || forward(2, &pending, &line));
        let (reply, _answer) = oneshot::channel();
        let request = SetRequest {
            parameter: "speed".into(),
            message: b"{\"value\": 1}".to_vec(),
            reply,
        };
        requests.send(request).unwrap();
        let (slot, got) = forwarded.recv().unwrap();
        assert_eq!((slot, got.parameter.as_str()), (2, "speed"));
        drop(requests);
        forwarder.join().unwrap();
        assert!(forwarded.recv().is_err(), "the line's sender went with it");
    }
}

//! A drive's bus side: a thread that owns the drive's session, reads its parameters every
//! interval, and answers set requests between polls. It reports the newest state only (a
//! `watch` channel): a slow broker sees the latest values, never a backlog.

use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::time::{Duration, Instant, SystemTime};

use drivebus::interpret::Shown;
use drivegen::ir::Parameter;
use tokio::sync::{oneshot, watch};

use super::exposed::Drive;
use super::payload;
use super::refusal::{Refusal, Refused};
use crate::commands::{read, write};
use crate::connect::Session;

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

/// Polls `drive` until `stop` turns true or the set requests' sender is gone.
pub fn run(
    drive: &Drive,
    requests: &Receiver<SetRequest>,
    reports: &watch::Sender<Report>,
    stop: &watch::Receiver<bool>,
) {
    let parameters: Vec<&Parameter> = drive
        .parameters
        .iter()
        .filter_map(|name| drive.parameter(name))
        .collect();
    let interval = Duration::from_millis(drive.interval_ms.into());
    let mut session = None;
    while !*stop.borrow() {
        let next = Instant::now() + interval;
        let report = poll(drive, &mut session, &parameters);
        log_change(&drive.name, &reports.borrow(), &report);
        reports.send_replace(report);
        loop {
            let left = next.saturating_duration_since(Instant::now());
            match requests.recv_timeout(left) {
                Ok(request) => answer(drive, &mut session, request),
                Err(RecvTimeoutError::Timeout) => break,
                Err(RecvTimeoutError::Disconnected) => return,
            }
        }
    }
}

/// One poll. A failed read drops the session, so the next poll reconnects (a restarted
/// server, a replugged adapter).
fn poll<'d>(
    drive: &'d Drive,
    session: &mut Option<Session<'d>>,
    parameters: &[&Parameter],
) -> Report {
    let open = match session {
        Some(open) => open,
        None => match Session::open(&drive.bus, &drive.device) {
            Ok(opened) => session.insert(opened),
            Err(e) => return Report::Failed(format!("cannot reach the drive: {e}")),
        },
    };
    match read::read_all(open, &drive.device, parameters) {
        Ok(values) => {
            let time = SystemTime::now();
            let payloads = parameters
                .iter()
                .zip(&values)
                .map(|(p, shown)| (p.name.clone(), payload::value(p, shown, time)))
                .collect();
            Report::Values(payloads)
        }
        Err(e) => {
            *session = None;
            Report::Failed(e.to_string())
        }
    }
}

/// Writes a set request through `drivegen write`'s checks and sends the result payload.
fn answer<'d>(drive: &'d Drive, session: &mut Option<Session<'d>>, request: SetRequest) {
    let parameter = drive.parameter(&request.parameter);
    let outcome = set(drive, session, parameter, &request.message);
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
    drive: &'d Drive,
    session: &mut Option<Session<'d>>,
    parameter: Option<&Parameter>,
    message: &[u8],
) -> Result<Shown, Refused> {
    let parameter =
        parameter.ok_or_else(|| Refused::new(Refusal::NotWritable, "no such parameter"))?;
    let text = payload::set_text(message).map_err(|why| Refused::new(Refusal::WrongType, why))?;
    let bytes = write::parse_value(&drive.device, parameter, &text).map_err(|e| Refused::of(&e))?;
    let open = session.as_mut().ok_or_else(|| {
        Refused::new(
            Refusal::Communication,
            "the drive is offline: nothing written",
        )
    })?;
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

//! `drivegen decode`: a candump capture as named, typed values.

use std::fmt;
use std::io::Write;
use std::path::PathBuf;

use crate::error::CliError;
use crate::frame_source::{FrameSource, LiveArgs, Received, Time};
use crate::frames::{Decoded, FrameDecoder};
use crate::objects::Objects;
use crate::table::Table;

/// Arguments of `decode`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
    /// candump log (`(1700000000.123456) can0 605#...`) or compact lines (`605#...`); none
    /// with --can.
    #[arg(required_unless_present = "can")]
    capture: Option<PathBuf>,
    #[command(flatten)]
    live: LiveArgs,
    /// Print one JSON object per frame.
    #[arg(long)]
    json: bool,
}

/// The JSON line of a frame or a bus error.
fn json(time: Time, node: &str, kind: &str, what: &str, value: &str) -> String {
    serde_json::json!({"time": time.to_string(), "node": node, "kind": kind, "object": what, "value": value})
        .to_string()
}

/// The JSON line of a decoded frame.
fn frame_json(time: Time, d: &Decoded<'_>) -> String {
    let (node, what, value) = (
        d.node().to_string(),
        d.what().to_string(),
        d.value().to_string(),
    );
    json(time, &node, d.kind(), &what, &value)
}

/// Decodes every frame of the capture (a table, or JSON lines), or live from --can (a line
/// each as it arrives).
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    let objects = Objects::new(&device);
    let mut decoder = FrameDecoder::new(&objects);
    let Some(capture) = &args.capture else {
        let source = FrameSource::live(&args.live, &device)?;
        return live(source, &mut decoder, args.json);
    };
    // Nothing is printed before the whole capture decoded: a malformed line fails the command.
    let mut table = Table::default();
    let mut json_lines = String::new();
    if !args.json {
        let header = ["time", "node", "kind", "object", "value"];
        table.row(header.iter().map(|h| h as &dyn fmt::Display));
    }
    for received in FrameSource::capture(capture)? {
        match received? {
            Received::Frame { time, frame } => {
                let d = decoder.decode(&frame);
                if args.json {
                    json_lines.push_str(&frame_json(time, &d));
                    json_lines.push('\n');
                } else {
                    let (node, value, what) = (d.node(), d.value(), d.what());
                    table.row([&time as &dyn fmt::Display, &node, &d.kind(), &what, &value]);
                }
            }
            Received::Malformed(reason) => return Err(CliError::Io(reason)),
            Received::BusError { .. } => {}
        }
    }
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    let written = if args.json {
        out.write_all(json_lines.as_bytes())
    } else {
        table.write(&mut out)
    };
    match written.and_then(|()| out.flush()) {
        // The reader went away (a closed pipe): nothing more to say.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other.map_err(|e| CliError::Io(format!("standard output: {e}"))),
    }
}

/// Decodes frames from a live interface as they arrive, one line (or JSON object) each; error
/// frames and bus states are lines of kind `error`.
fn live(
    source: FrameSource,
    decoder: &mut FrameDecoder<'_>,
    json_lines: bool,
) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    for received in source {
        let printed = match received? {
            Received::Frame { time, frame } => {
                let d = decoder.decode(&frame);
                if json_lines {
                    writeln!(out, "{}", frame_json(time, &d))
                } else {
                    writeln!(
                        out,
                        "{time}  {}  {}  {}  {}",
                        d.node(),
                        d.kind(),
                        d.what(),
                        d.value()
                    )
                }
            }
            Received::BusError {
                time,
                classes,
                state,
            } => {
                if json_lines {
                    writeln!(out, "{}", json(time, "", "error", &classes, &state))
                } else {
                    writeln!(out, "{time}    error  {classes}  {state}")
                }
            }
            Received::Malformed(_) => continue,
        };
        if printed.and_then(|()| out.flush()).is_err() {
            // The reader went away (a closed pipe): stop quietly.
            return Ok(());
        }
    }
    Ok(())
}

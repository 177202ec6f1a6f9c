//! `drivegen decode`: a candump capture as named, typed values.

use std::io::Write;
use std::path::PathBuf;

use crate::error::CliError;
use crate::frame_source::{FrameSource, LiveArgs, Received};
use crate::frames::{Decoded, FrameDecoder};
use crate::table;

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

/// One decoded frame, or a bus error of a live interface.
struct Line {
    time: String,
    node: String,
    kind: &'static str,
    what: String,
    value: String,
}

impl Line {
    fn of(time: String, d: Decoded) -> Self {
        Self {
            time,
            node: d.node,
            kind: d.kind,
            what: d.what,
            value: d.value,
        }
    }

    fn json(&self) -> String {
        serde_json::json!({"time": self.time, "node": self.node, "kind": self.kind, "object": self.what, "value": self.value})
            .to_string()
    }
}

/// Decodes every frame of the capture (a table, or JSON lines), or live from --can (a line
/// each as it arrives).
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    let mut decoder = FrameDecoder::new(&device);
    let Some(capture) = &args.capture else {
        let source = FrameSource::live(&args.live, &device)?;
        return live(source, &mut decoder, args.json);
    };
    let mut lines = Vec::new();
    for received in FrameSource::capture(capture)? {
        match received? {
            Received::Frame { time, frame } => lines.push(Line::of(time, decoder.decode(&frame))),
            Received::Malformed(reason) => return Err(CliError::Io(reason)),
            Received::BusError { .. } => {}
        }
    }
    if args.json {
        for l in &lines {
            println!("{}", l.json());
        }
    } else {
        let mut rows = vec![vec![
            "time".to_string(),
            "node".into(),
            "kind".into(),
            "object".into(),
            "value".into(),
        ]];
        rows.extend(
            lines
                .into_iter()
                .map(|l| vec![l.time, l.node, l.kind.to_string(), l.what, l.value]),
        );
        print!("{}", table::render(&rows));
    }
    Ok(())
}

/// Decodes frames from a live interface as they arrive, one line (or JSON object) each; error
/// frames and bus states are lines of kind `error`.
fn live(source: FrameSource, decoder: &mut FrameDecoder<'_>, json: bool) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    for received in source {
        let line = match received? {
            Received::Frame { time, frame } => Line::of(time, decoder.decode(&frame)),
            Received::BusError {
                time,
                classes,
                state,
            } => Line {
                time,
                node: String::new(),
                kind: "error",
                what: classes,
                value: state,
            },
            Received::Malformed(_) => continue,
        };
        let printed = if json {
            writeln!(out, "{}", line.json())
        } else {
            writeln!(
                out,
                "{}  {}  {}  {}  {}",
                line.time, line.node, line.kind, line.what, line.value
            )
        };
        if printed.and_then(|()| out.flush()).is_err() {
            // The reader went away (a closed pipe): stop quietly.
            return Ok(());
        }
    }
    Ok(())
}

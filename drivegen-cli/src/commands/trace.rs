//! `drivegen trace`: a bus decoded passively, from a candump log or live, every frame named and
//! typed with its time; filters by node and parameter; a trigger that keeps a window of frames
//! before and after it; table, CSV or JSON lines.

use std::collections::BTreeSet;
use std::path::PathBuf;

use drivebus::canopen::CanFrame;
use drivebus::trace::{Armed, Captured, Trigger, Window};
use serde_json::json;

use crate::csv;
use crate::error::CliError;
use crate::frame_source::{FrameSource, Received, Time};
use crate::frames::{Decoded, FrameDecoder};
use crate::lines::Lines;
use crate::objects::Objects;
use crate::series::plot_file::PlotFile;
use crate::series::plotter::Plotter;

/// Arguments of `trace`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
    /// candump log (`(1700000000.123456) can0 605#...`) or compact lines (`605#...`); none
    /// with --can.
    #[arg(required_unless_present = "can")]
    capture: Option<PathBuf>,
    #[command(flatten)]
    live: crate::frame_source::LiveArgs,
    /// Only frames from or to this node (repeatable).
    #[arg(long = "node", value_name = "ID")]
    nodes: Vec<u8>,
    /// Only frames that carry this parameter, showing only the chosen ones (repeatable).
    #[arg(long = "parameter", value_name = "NAME")]
    parameters: Vec<String>,
    /// Keep only windows around this trigger: NAME>LEVEL or NAME<LEVEL (a level crossed, in
    /// the parameter's unit), emcy, or nmt (an NMT command or a node's changed state).
    #[arg(long)]
    trigger: Option<Trigger>,
    /// With --trigger: frames kept before the trigger.
    #[arg(long, default_value_t = 10, requires = "trigger")]
    pre: usize,
    /// With --trigger: frames kept after the trigger.
    #[arg(long, default_value_t = 10, requires = "trigger")]
    post: usize,
    /// Comma-separated values with a header line.
    #[arg(long, conflicts_with = "json")]
    csv: bool,
    /// One JSON object per frame.
    #[arg(long)]
    json: bool,
    /// Also draw the samples of the frames shown into FILE.svg or FILE.html (a panel per
    /// parameter, in its unit; the HTML zooms).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

/// Where a row stands in a captured window.
#[derive(Debug, Clone, Copy)]
struct Place {
    window: usize,
    at: &'static str,
}

/// A frame as printed.
#[derive(Debug, Clone)]
struct Row<'a> {
    time: Time,
    decoded: Decoded<'a>,
}

/// Runs `trace`.
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    for name in &args.parameters {
        super::parameter(&device, name)?;
    }
    if let Some(Trigger::Crosses { parameter, .. }) = &args.trigger {
        super::parameter(&device, parameter)?;
    }
    let plot = args.plot.as_deref().map(PlotFile::create).transpose()?;
    let source = match &args.capture {
        Some(path) => FrameSource::capture(path)?,
        None => FrameSource::live(&args.live, &device)?,
    };
    let live = args.capture.is_none();
    let mut out = Output::new(&args, live);
    out.plot = plot.map(|file| Plotter::new(file, &device, "trace", &[]).redrawn(live));
    let objects = Objects::new(&device);
    let mut trace = Trace::new(&args, &objects);
    for received in source {
        if out.out.is_closed() {
            break;
        }
        match received? {
            Received::Frame { time, frame } => trace.frame(time, &frame, &mut out)?,
            Received::Malformed(reason) => {
                trace.malformed += 1;
                trace.first_malformed.get_or_insert(reason);
            }
            Received::BusError { .. } => trace.bus_errors += 1,
        }
    }
    trace.finish(&mut out)?;
    out.out.flush()?;
    if let Some(plot) = &mut out.plot {
        plot.finish()?;
    }
    if trace.bus_errors > 0 {
        eprintln!("the interface reported {} bus error(s)", trace.bus_errors);
    }
    if let Some(first) = &trace.first_malformed {
        eprintln!(
            "skipped {} malformed line(s); the first: {first}",
            trace.malformed
        );
    }
    Ok(())
}

/// The filters, trigger and window of one run.
struct Trace<'a> {
    decoder: FrameDecoder<'a>,
    nodes: BTreeSet<u8>,
    parameters: BTreeSet<String>,
    trigger: Option<(Armed, Window<Row<'a>>)>,
    windows: usize,
    /// Lines that were not frames: how many, and where and why the first.
    malformed: usize,
    first_malformed: Option<String>,
    bus_errors: usize,
}

impl<'a> Trace<'a> {
    fn new(args: &Args, objects: &'a Objects<'a>) -> Self {
        Self {
            decoder: FrameDecoder::new(objects),
            nodes: args.nodes.iter().copied().collect(),
            parameters: args.parameters.iter().cloned().collect(),
            trigger: args
                .trigger
                .clone()
                .map(|t| (t.arm(), Window::new(args.pre, args.post))),
            windows: 0,
            malformed: 0,
            first_malformed: None,
            bus_errors: 0,
        }
    }

    /// Decodes a frame and takes it; a frame of another node is dropped before it becomes a
    /// row, unless a trigger may fire on it.
    fn frame(&mut self, time: Time, frame: &CanFrame, out: &mut Output) -> Result<(), CliError> {
        let decoded = self.decoder.decode(frame);
        if self.trigger.is_none() && !self.node_ok(&decoded) {
            return Ok(());
        }
        self.take(Row { time, decoded }, out)
    }

    fn node_ok(&self, decoded: &Decoded<'_>) -> bool {
        self.nodes.is_empty() || decoded.node_id().is_some_and(|n| self.nodes.contains(&n))
    }

    /// The row as the filters leave it: `None` if they drop it.
    fn filtered(&self, mut row: Row<'a>) -> Option<Row<'a>> {
        if !self.node_ok(&row.decoded) {
            return None;
        }
        if self.parameters.is_empty() || row.decoded.keep_parameters(&self.parameters) {
            return Some(row);
        }
        None
    }

    fn take(&mut self, row: Row<'a>, out: &mut Output) -> Result<(), CliError> {
        let Some((armed, _)) = &mut self.trigger else {
            return match self.filtered(row) {
                Some(row) => out.row(&row, None),
                None => Ok(()),
            };
        };
        let fired = row.decoded.events().any(|e| armed.fires(&e));
        // The frame that fires is kept whatever the filters say.
        let row = if fired { Some(row) } else { self.filtered(row) };
        let Some(row) = row else { return Ok(()) };
        let captured = self.trigger.as_mut().and_then(|(_, w)| w.push(row, fired));
        match captured {
            Some(captured) => self.print_window(captured, out),
            None => Ok(()),
        }
    }

    fn finish(&mut self, out: &mut Output) -> Result<(), CliError> {
        let last = self.trigger.take().and_then(|(_, w)| w.finish());
        match last {
            Some(captured) => self.print_window(captured, out),
            None => Ok(()),
        }
    }

    fn print_window(
        &mut self,
        captured: Captured<Row<'a>>,
        out: &mut Output,
    ) -> Result<(), CliError> {
        self.windows += 1;
        let window = self.windows;
        out.window_header(window, &captured)?;
        let place = |at| Some(Place { window, at });
        for row in &captured.before {
            out.row(row, place("before"))?;
        }
        out.row(&captured.trigger, place("trigger"))?;
        for row in &captured.after {
            out.row(row, place("after"))?;
        }
        Ok(())
    }
}

/// Rows as the chosen format prints them, to standard output as they come, and to the plot.
struct Output<'d> {
    format: Format,
    out: Lines,
    header_done: bool,
    plot: Option<Plotter<'d>>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Lines,
    Csv,
    Json,
}

impl Output<'_> {
    /// The output of `args`; a live source's rows reach the reader as they come.
    fn new(args: &Args, live: bool) -> Self {
        let format = match (args.csv, args.json) {
            (true, _) => Format::Csv,
            (_, true) => Format::Json,
            _ => Format::Lines,
        };
        Self {
            format,
            out: if live {
                Lines::stdout()
            } else {
                Lines::buffered()
            },
            header_done: false,
            plot: None,
        }
    }

    /// Writes a line; a reader that went away (a closed pipe) ends the output quietly.
    fn write(&mut self, line: &str) -> Result<(), CliError> {
        self.out.write(line)
    }

    fn window_header(
        &mut self,
        window: usize,
        captured: &Captured<Row<'_>>,
    ) -> Result<(), CliError> {
        if self.format != Format::Lines {
            return Ok(());
        }
        let incomplete = if captured.complete {
            ""
        } else {
            ", the input ended before the window did"
        };
        self.write(&format!(
            "# window {window}: triggered at {} ({} before, {} after{incomplete})",
            captured.trigger.time,
            captured.before.len(),
            captured.after.len()
        ))
    }

    fn row(&mut self, row: &Row<'_>, place: Option<Place>) -> Result<(), CliError> {
        let d = &row.decoded;
        if let Some(plot) = &mut self.plot {
            plot.frame(&row.time.to_string(), d.samples())?;
        }
        match self.format {
            Format::Lines => self.out.line(format_args!(
                "{}  {}  {}  {}  {}",
                row.time,
                d.node(),
                d.kind(),
                d.what(),
                d.value()
            )),
            Format::Csv => {
                if !self.header_done {
                    self.header_done = true;
                    self.write("window,at,time,node,kind,object,value")?;
                }
                let (window, at) =
                    place.map_or((String::new(), ""), |p| (p.window.to_string(), p.at));
                let (time, node) = (row.time.to_string(), d.node().to_string());
                let (what, value) = (d.what().to_string(), d.value().to_string());
                let fields = [&window, at, &time, &node, d.kind(), &what, &value];
                self.write(&csv::record(&fields))
            }
            Format::Json => {
                let samples: serde_json::Map<String, serde_json::Value> = d
                    .samples()
                    .iter()
                    .map(|s| {
                        let value = s
                            .value()
                            .map_or_else(|| json!(s.text().to_string()), |v| json!(v));
                        (s.parameter().to_string(), value)
                    })
                    .collect();
                let line = json!({
                    "window": place.map(|p| p.window),
                    "at": place.map(|p| p.at),
                    "time": row.time.to_string(),
                    "node": d.node().to_string(),
                    "kind": d.kind(),
                    "object": d.what().to_string(),
                    "value": d.value().to_string(),
                    "samples": samples,
                });
                self.write(&line.to_string())
            }
        }
    }
}

//! `drivegen watch`: poll parameters and show them live, one line per poll.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use drivegen::ir::{Device, Parameter};

use crate::connect::BusArgs;
use crate::drives::{self, Drives, Outcome};
use crate::error::CliError;
use crate::series::plot_file::PlotFile;
use crate::series::plotter::Plotter;

/// Arguments of `watch`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Description file, or a folder with a device.toml.
    description: PathBuf,
    /// Parameter names.
    #[arg(required = true)]
    parameters: Vec<String>,
    #[command(flatten)]
    bus: BusArgs,
    /// Milliseconds between polls.
    #[arg(long, default_value_t = 500)]
    interval_ms: u64,
    /// Stop after this many polls (default: until interrupted).
    #[arg(long)]
    count: Option<u64>,
    /// Print one JSON object per poll.
    #[arg(long)]
    json: bool,
    /// Also draw the values into FILE.svg or FILE.html (a panel per parameter, in its unit;
    /// the HTML zooms), drawn again as the watch goes on. One drive only.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// A live terminal scope instead of lines: a chart per parameter, `space` pauses, `q`
    /// quits. One drive only.
    #[arg(long, conflicts_with_all = ["json", "count"])]
    tui: bool,
}

/// Polls until `--count` is reached or the process is interrupted: one drive a line per poll,
/// several drives a block of rows per poll with a column per drive.
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    let parameters = super::read::resolve(&device, &args.parameters)?;
    crate::series::one_drive(&args.bus, args.plot.is_some(), "--plot")?;
    crate::series::one_drive(&args.bus, args.tui, "--tui")?;
    let plot = args.plot.as_deref().map(PlotFile::create).transpose()?;
    let mut plot = plot.map(|file| Plotter::new(file, &device, "watch", &parameters));
    let mut drives = Drives::open(&args.bus, &device)?;
    let Some(session) = drives.single() else {
        return watch_each(&args, &device, &parameters, &mut drives);
    };
    if args.tui {
        let interval = Duration::from_millis(args.interval_ms);
        let poll = || super::read::read_all(session, &device, &parameters);
        return crate::series::tui::run(&device, &parameters, interval, plot, poll);
    }
    let widths: Vec<usize> = parameters.iter().map(|p| p.name.len().max(12)).collect();
    if !args.json {
        let header: Vec<String> = parameters
            .iter()
            .zip(&widths)
            .map(|(p, w)| format!("{:<w$}", p.name))
            .collect();
        println!("{:>8}  {}", "time", header.join("  "));
    }
    let start = Instant::now();
    let mut polls = 0;
    while args.count.is_none_or(|n| polls < n) {
        let values = super::read::read_all(session, &device, &parameters)?;
        let elapsed = start.elapsed().as_secs_f64();
        if let Some(plot) = &mut plot {
            plot.poll(&parameters, &values, elapsed)?;
        }
        if args.json {
            let fields = by_name(&parameters, &values);
            println!(
                "{}",
                serde_json::json!({ "time": elapsed, "values": fields })
            );
        } else {
            let cells: Vec<String> = values
                .iter()
                .zip(&widths)
                .map(|(s, w)| format!("{:<w$}", s.text))
                .collect();
            println!("{elapsed:>7.1}s  {}", cells.join("  ").trim_end());
        }
        polls += 1;
        if args.count.is_none_or(|n| polls < n) {
            std::thread::sleep(Duration::from_millis(args.interval_ms));
        }
    }
    plot.map_or(Ok(()), |mut plot| plot.finish())
}

/// Polls every drive until `--count` is reached or the process is interrupted. A drive that
/// fails shows its error in its column and is asked again at the next poll; the others go on.
/// Fails at the end when any drive failed at any poll.
fn watch_each(
    args: &Args,
    device: &Device,
    parameters: &[&Parameter],
    drives: &mut Drives<'_>,
) -> Result<(), CliError> {
    let headers = drives.headers();
    let name_width = parameters.iter().map(|p| p.name.len()).max().unwrap_or(0);
    let widths: Vec<usize> = headers.iter().map(|h| h.len().max(12)).collect();
    let line = |time: &str, name: &str, cells: &[String]| {
        let cells: Vec<String> = cells
            .iter()
            .zip(&widths)
            .map(|(cell, w)| format!("{cell:<w$}"))
            .collect();
        let line = format!("{time:>8}  {name:<name_width$}  {}", cells.join("  "));
        println!("{}", line.trim_end());
    };
    if !args.json {
        line("time", "parameter", &headers);
    }
    let mut failed = vec![false; drives.len()];
    let start = Instant::now();
    let mut polls = 0;
    while args.count.is_none_or(|n| polls < n) {
        let outcomes = drives.read_each(device, parameters);
        let elapsed = start.elapsed().as_secs_f64();
        for (failed, outcome) in failed.iter_mut().zip(&outcomes) {
            *failed |= outcome.is_err();
        }
        if args.json {
            println!("{}", poll_json(drives, parameters, &outcomes, elapsed));
        } else {
            for (i, row) in drives::rows(parameters, &outcomes).iter().enumerate() {
                let time = if i == 0 {
                    format!("{elapsed:.1}s")
                } else {
                    String::new()
                };
                line(&time, &row[0], &row[1..]);
            }
        }
        polls += 1;
        if args.count.is_none_or(|n| polls < n) {
            std::thread::sleep(Duration::from_millis(args.interval_ms));
        }
    }
    match failed.iter().filter(|f| **f).count() {
        0 => Ok(()),
        failed => Err(CliError::DrivesFailed {
            failed,
            asked: drives.len(),
        }),
    }
}

/// One poll of every drive as a JSON object: `{"time": 0.5, "drives": [...]}`, each drive's
/// values by parameter name as one drive's poll gives them.
fn poll_json(
    drives: &Drives<'_>,
    parameters: &[&Parameter],
    outcomes: &[Outcome],
    elapsed: f64,
) -> serde_json::Value {
    let values = |shown: &[drivebus::interpret::Shown]| by_name(parameters, shown);
    serde_json::json!({ "time": elapsed, "drives": drives.to_json(outcomes, values) })
}

/// One drive's values of one poll, by parameter name.
fn by_name(parameters: &[&Parameter], shown: &[drivebus::interpret::Shown]) -> serde_json::Value {
    let fields: serde_json::Map<String, serde_json::Value> = parameters
        .iter()
        .zip(shown)
        .map(|(p, s)| (p.name.clone(), super::read::to_json(p, s)))
        .collect();
    fields.into()
}

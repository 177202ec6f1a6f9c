//! `drivegen watch`: parameters shown live, sample by sample, until `--count` or Ctrl-C. How
//! samples are got (`source_*.rs`: polling, PDOs) and how they are shown (`output_*.rs`: lines,
//! JSON, CSV) meet in [`sample`]: a stream of times with a typed value per parameter per drive.

pub mod interrupt;
mod output_csv;
mod output_json;
mod output_lines;
mod output_plot;
pub mod pdo_plan;
mod pdo_slots;
pub mod sample;
pub mod source_pdo;
mod source_poll;
mod tpdo_config;
pub mod tpdo_notice;
pub mod tpdo_setup;

use std::path::PathBuf;
use std::time::Duration;

use self::interrupt::Interrupt;
use self::pdo_plan::Trigger;
use self::sample::{Layout, Output, Source};
use self::source_pdo::{PdoWatch, Settings};
use self::source_poll::Poll;
use self::tpdo_setup::TpdoSetup;
use drivegen::ir::Device;

use crate::connect::BusArgs;
use crate::drives::Drives;
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
    /// Milliseconds between samples (polls, or SYNCs with --pdo).
    #[arg(long, default_value_t = 500)]
    interval_ms: u64,
    /// Stop after this many samples (default: until interrupted; Ctrl-C ends the watch cleanly).
    #[arg(long)]
    count: Option<u64>,
    /// Print one JSON object per sample.
    #[arg(long, conflicts_with = "csv")]
    json: bool,
    /// Print CSV: one header (each column a parameter, with its unit; several drives: a column
    /// per parameter per drive), then a row per sample.
    #[arg(long)]
    csv: bool,
    /// CANopen: take the values from a TPDO instead of SDO polls, with no SDO request while
    /// watching. A TPDO that already carries the parameters (sent at every SYNC, or by its
    /// event timer with --event-timer) is used as it is;
    /// otherwise the parameters are mapped into one of the described TPDOs (an unused one
    /// first), and its configuration, read first, is written back when the watch ends (Ctrl-C
    /// included). The watch sends a SYNC every --interval-ms.
    #[arg(long)]
    pdo: bool,
    /// --pdo: the drive sends the TPDO by its event timer every --interval-ms instead of at
    /// SYNC (no SYNC is sent).
    #[arg(long, requires = "pdo")]
    event_timer: bool,
    /// --pdo: send NMT Start to the nodes before watching (a node sends PDOs only while
    /// Operational) and NMT Enter Pre-Operational after.
    #[arg(long, requires = "pdo")]
    start: bool,
    /// Also draw the values into FILE.svg or FILE.html (a panel per parameter, in its unit;
    /// the HTML zooms), drawn again as the watch goes on. One drive only.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// A live terminal scope instead of lines: a chart per parameter, `space` pauses, `q`
    /// quits. One drive only.
    #[arg(long, conflicts_with_all = ["json", "csv", "count"])]
    tui: bool,
}

/// Watches until `--count` samples were shown or the process is interrupted: one drive a line
/// per sample, several drives a block of rows per sample with a column per drive (or JSON, or
/// CSV).
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    let parameters = super::read::resolve(&device, &args.parameters)?;
    crate::series::one_drive(&args.bus, args.plot.is_some(), "--plot")?;
    crate::series::one_drive(&args.bus, args.tui, "--tui")?;
    // Created before the bus opens: a path that cannot be written is refused first.
    let plot = args.plot.as_deref().map(PlotFile::create).transpose()?;
    let plot = plot.map(|file| Plotter::new(file, &device, "watch", &parameters));
    // `--pdo` sends SYNC and NMT beside its transfers: its nodes share one client on the bus.
    let mut drives = match args.pdo {
        true => Drives::open_on_one_client(&args.bus, &device)?,
        false => Drives::open(&args.bus, &device)?,
    };
    let interrupt = Interrupt::catch()?;
    let layout = Layout {
        parameters: &parameters,
        drives: drives.ids(),
    };
    let interval = Duration::from_millis(args.interval_ms);
    if !args.pdo {
        let mut source = Poll::new(&mut drives, &device, &parameters, interval, interrupt);
        return show(&args, &device, &layout, &mut source, plot);
    }
    if args.interval_ms == 0 {
        return Err(CliError::Usage(
            "--pdo: give --interval-ms of at least 1 (a SYNC every interval)".into(),
        ));
    }
    let trigger = match args.event_timer {
        false => Trigger::Sync,
        true => Trigger::EventTimer(u16::try_from(args.interval_ms).map_err(|_| {
            CliError::Usage("--event-timer: --interval-ms is at most 65535".into())
        })?),
    };
    let settings = Settings {
        trigger,
        interval,
        timeout: Duration::from_millis(args.bus.timeout_ms),
        start: args.start,
    };
    let setup = TpdoSetup::begin(
        drives.sessions(),
        &device,
        &parameters,
        trigger,
        args.start,
        &[],
        tpdo_notice::on_stderr,
    )?;
    let mut source = PdoWatch::new(setup, settings, interrupt);
    let watched = show(&args, &device, &layout, &mut source, plot);
    // Restored here to report a failure; on an early return `Drop` restores.
    let restored = source.restore();
    watched.and(restored)
}

/// Shows the samples of `source` the way the options ask: the terminal scope, or printed (and
/// drawn into the plot, if any).
fn show<'d>(
    args: &Args,
    device: &Device,
    layout: &Layout<'_>,
    source: &mut dyn Source,
    plot: Option<Plotter<'d>>,
) -> Result<(), CliError> {
    if args.tui {
        let interval = Duration::from_millis(args.interval_ms);
        let poll = || match source.next()? {
            Some(mut sample) => sample.drives.pop().unwrap_or_else(|| Ok(Vec::new())),
            None => Err(CliError::Io("interrupted".into())),
        };
        return crate::series::tui::run(device, layout.parameters, interval, plot, poll);
    }
    let mut output = output(args, plot);
    watch(args.count, layout, source, output.as_mut())?;
    output.end()
}

/// The output the options ask for.
fn output<'d>(args: &Args, plot: Option<Plotter<'d>>) -> Box<dyn Output + 'd> {
    let printed: Box<dyn Output> = match (args.csv, args.json) {
        (true, _) => Box::new(output_csv::CsvOutput::new()),
        (_, true) => Box::new(output_json::JsonOutput::new()),
        _ => Box::new(output_lines::LinesOutput::new()),
    };
    match plot {
        Some(plotter) => Box::new(output_plot::PlotOutput { printed, plotter }),
        None => printed,
    }
}

/// Shows samples from `source` until `count` or an interruption. One drive: its failure ends
/// the watch. Several: a drive that fails shows its error and is asked again at the next
/// sample; the watch fails at the end when any drive failed at any sample.
fn watch(
    count: Option<u64>,
    layout: &Layout<'_>,
    source: &mut dyn Source,
    output: &mut dyn Output,
) -> Result<(), CliError> {
    output.begin(layout)?;
    let mut failed = vec![false; layout.drives.len()];
    let mut samples = 0;
    while count.is_none_or(|n| samples < n) {
        let Some(mut sample) = source.next()? else {
            break;
        };
        if layout.single() && sample.drives.first().is_some_and(Result::is_err) {
            if let Some(Err(e)) = sample.drives.pop() {
                return Err(e);
            }
        }
        for (failed, outcome) in failed.iter_mut().zip(&sample.drives) {
            *failed |= outcome.is_err();
        }
        output.sample(layout, &sample)?;
        samples += 1;
    }
    match failed.iter().filter(|f| **f).count() {
        0 => Ok(()),
        failed => Err(CliError::DrivesFailed {
            failed,
            asked: layout.drives.len(),
        }),
    }
}

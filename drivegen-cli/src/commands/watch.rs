//! `drivegen watch`: poll parameters and show them live, one line per poll.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crate::connect::{BusArgs, Session};
use crate::error::CliError;

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
}

/// Polls until `--count` is reached or the process is interrupted.
pub fn run(args: Args) -> Result<(), CliError> {
    let device = super::load(&args.description)?;
    let parameters = super::read::resolve(&device, &args.parameters)?;
    let mut session = Session::open(&args.bus, &device)?;
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
        let values = super::read::read_all(&mut session, &device, &parameters)?;
        let elapsed = start.elapsed().as_secs_f64();
        if args.json {
            let fields: serde_json::Map<String, serde_json::Value> = parameters
                .iter()
                .zip(&values)
                .map(|(p, s)| (p.name.clone(), super::read::to_json(p, s)))
                .collect();
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
    Ok(())
}

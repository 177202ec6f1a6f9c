//! Four simulated drives, one per family, each on its own protocol, driven at once from four
//! tokio tasks through the async typed API: a Lafert Smartris on Modbus TCP, a Lenze smd on
//! Modbus RTU over TCP, an ez-Wheel SWD on CANopen (SLCAN over TCP) and a Kinco FD on its RS-232
//! protocol (an in-memory serial line). Each is enabled where it needs it and given a speed; their
//! live values are printed side by side every 500 ms; then each is stopped (setpoint 0 and its
//! stop command) and the program exits.
//!
//! ```sh
//! cargo run -p drivegen-examples --example async_fleet -- --seconds 5
//! ```

use std::error::Error;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use tokio::sync::watch;

mod fleet;

use fleet::{kinco, lafert, lenze, swd, Live, Outcome};

/// How long the drives run unless `--seconds N` says otherwise.
const DEFAULT_SECONDS: f64 = 5.0;
/// One printed line per this period.
const LINE_PERIOD: Duration = Duration::from_millis(500);

#[tokio::main]
async fn main() -> Result<(), Box<dyn Error + Send + Sync>> {
    let seconds = seconds_from_args()?;
    let live: Live = Arc::new(Mutex::new(fleet::NAMES.map(|_| String::from("starting"))));
    let (stop, stopping) = watch::channel(false);
    let tasks = [
        tokio::spawn(lafert::run(Arc::clone(&live), stopping.clone())),
        tokio::spawn(lenze::run(Arc::clone(&live), stopping.clone())),
        tokio::spawn(swd::run(Arc::clone(&live), stopping.clone())),
        tokio::spawn(kinco::run(Arc::clone(&live), stopping)),
    ];
    print_row("time", &fleet::NAMES.map(String::from));
    let lines = (seconds / LINE_PERIOD.as_secs_f64()).ceil() as u32;
    for line in 1..=lines {
        tokio::time::sleep(LINE_PERIOD).await;
        let time = format!("{:.1} s", f64::from(line) * LINE_PERIOD.as_secs_f64());
        let values = live.lock().map_err(|_| "a drive task panicked")?.clone();
        print_row(&time, &values);
    }
    stop.send(true)?;
    let mut failed = false;
    for (name, task) in fleet::NAMES.iter().zip(tasks) {
        let outcome: Outcome = task.await?;
        match outcome {
            Ok(last) => println!("{name:<17} stopped: {last}"),
            Err(why) => {
                failed = true;
                println!("{name:<17} failed: {why}");
            }
        }
    }
    if failed {
        return Err("a drive failed".into());
    }
    Ok(())
}

fn print_row(first: &str, columns: &[String; 4]) {
    println!(
        "{first:<7} {:<24} {:<24} {:<24} {:<24}",
        columns[0], columns[1], columns[2], columns[3]
    );
}

/// `--seconds N` (fractions allowed), else the default.
fn seconds_from_args() -> Result<f64, Box<dyn Error + Send + Sync>> {
    let mut args = std::env::args().skip(1);
    match (args.next().as_deref(), args.next()) {
        (None, _) => Ok(DEFAULT_SECONDS),
        (Some("--seconds"), Some(value)) => Ok(value.parse::<f64>()?.clamp(0.5, 600.0)),
        _ => Err("usage: async_fleet [--seconds N]".into()),
    }
}

//! `soak`: many transactions against the simulator through a fault-injecting proxy,
//! over Modbus TCP, Modbus RTU on a pty and SDO over candump; every value read is checked against
//! the simulator, and non-idempotent writes must never be repeated.
//!
//! ```text
//! cargo run --release -p soak -- [--transactions N] [--seed S] [--fault-rate P]
//!                                         [--transport modbus-tcp|modbus-rtu|sdo-candump]...
//!                                         [--max-seconds S]
//! cargo run -p soak -- --list-transports
//! ```
//!
//! Exits non-zero when a wrong value was delivered, a reported write is not held, or a
//! non-idempotent write was sent twice. See docs/reliability.md.

mod endpoint;
mod fault;
mod proxy;
mod resources;
mod rng;
mod run;
mod tally;
mod transports;
mod truth;

use std::process::ExitCode;
use std::time::{Duration, Instant};

use drivesim::Simulator;

use crate::fault::FaultCounts;
use crate::rng::Rng;
use crate::tally::Report;
use crate::transports::Transport;
use crate::truth::Truth;

/// The command line.
#[derive(Debug)]
struct Options {
    transactions: u64,
    seed: u64,
    fault_rate: f64,
    transports: Vec<Transport>,
    /// Stops each transport's run after this many seconds (the report says how many ran).
    max_seconds: Option<u64>,
    /// Prints the transports' names instead of running (scripts/soak-smoke runs each in its own
    /// process).
    list_transports: bool,
}

fn value<T: std::str::FromStr>(flag: &str, text: Option<String>) -> Result<T, String> {
    text.and_then(|t| t.replace('_', "").parse().ok())
        .ok_or_else(|| format!("{flag} needs a number"))
}

fn parse(mut args: impl Iterator<Item = String>) -> Result<Options, String> {
    let mut options = Options {
        transactions: 1_000_000,
        seed: 23,
        fault_rate: 0.01,
        transports: Vec::new(),
        max_seconds: None,
        list_transports: false,
    };
    while let Some(flag) = args.next() {
        match flag.as_str() {
            "--transactions" => options.transactions = value(&flag, args.next())?,
            "--seed" => options.seed = value(&flag, args.next())?,
            "--fault-rate" => options.fault_rate = value(&flag, args.next())?,
            "--max-seconds" => options.max_seconds = Some(value(&flag, args.next())?),
            "--list-transports" => options.list_transports = true,
            "--transport" => {
                let name = args.next().unwrap_or_default();
                let transport = Transport::ALL
                    .into_iter()
                    .find(|t| t.name() == name)
                    .ok_or_else(|| format!("unknown transport {name:?}"))?;
                options.transports.push(transport);
            }
            other => return Err(format!("unknown argument {other:?}")),
        }
    }
    if options.transports.is_empty() {
        options.transports = Transport::ALL.to_vec();
    }
    Ok(options)
}

fn fixture() -> Result<Simulator, String> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/soak-device.toml");
    Simulator::load(path).map_err(|e| format!("{path}: {e}"))
}

/// Soaks one transport on a fresh simulator; whether it stayed clean.
fn soak(transport: Transport, options: &Options) -> Result<bool, String> {
    let sim = fixture()?;
    let truth = Truth::new(&sim)?;
    let counts: &'static FaultCounts = Box::leak(Box::default());
    let plan = transport.plan(options.fault_rate);
    let (mut endpoint, _guard) = transport.connect(&sim, plan, options.seed, counts)?;
    let mut rng = Rng::stream(options.seed, transport.name());
    let deadline = options
        .max_seconds
        .map(|seconds| Instant::now() + Duration::from_secs(seconds));
    let tally = run::soak(
        endpoint.as_mut(),
        &truth,
        options.transactions,
        deadline,
        &mut rng,
    );
    print!(
        "{}",
        Report {
            transport: transport.name(),
            tally: &tally,
            faults: counts,
        }
    );
    Ok(tally.clean())
}

fn main() -> ExitCode {
    let options = match parse(std::env::args().skip(1)) {
        Ok(options) => options,
        Err(error) => {
            eprintln!("soak: {error}");
            return ExitCode::from(2);
        }
    };
    if options.list_transports {
        for transport in Transport::ALL {
            println!("{}", transport.name());
        }
        return ExitCode::SUCCESS;
    }
    println!(
        "soak: {} transactions per transport, seed {}, fault rate {}",
        options.transactions, options.seed, options.fault_rate
    );
    let mut clean = true;
    for &transport in &options.transports {
        match soak(transport, &options) {
            Ok(ok) => clean &= ok,
            Err(error) => {
                eprintln!("soak: {error}");
                return ExitCode::from(2);
            }
        }
    }
    if clean {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

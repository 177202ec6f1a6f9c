//! The `drivegen` command-line tool: validate and inspect descriptions, generate drive crates,
//! simulate a drive, and read, write, watch or decode a drive's values by parameter name.

mod at_once;
mod can;
mod can_sdo;
mod codec;
mod commands;
mod connect;
mod csv;
mod drives;
mod error;
mod frame_source;
mod frames;
mod identity_check;
mod lines;
mod objects;
mod pdo_mappings;
mod series;
mod suggest;
mod table;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Typed Rust driver crates for industrial motor drives, from device descriptions.
#[derive(Parser)]
#[command(name = "drivegen", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Validate a description and print diagnostics (exit code 1 on errors).
    Check(commands::check::Args),
    /// Print the normalized device model (a table, or the IR JSON with --json).
    Dump(commands::dump::Args),
    /// Compare two descriptions: what changed, and whether it breaks code (exit code 1 if so).
    Diff(commands::diff::Args),
    /// Create a drive crate that builds at once: a description skeleton or a vendor EDS overlay.
    New(commands::new::Args),
    /// Generate a standalone drive crate (Cargo.toml + src/lib.rs) into a folder.
    Generate(commands::generate::Args),
    /// Simulate the described drive on Modbus TCP, Modbus RTU or CANopen until interrupted.
    Sim(commands::sim::Args),
    /// Read parameters by name and print them in engineering units.
    Read(commands::read::Args),
    /// Write one parameter by name; the value is checked against the description first.
    Write(commands::write::Args),
    /// Poll parameters and show them live.
    Watch(commands::watch::Args),
    /// Decode a candump capture into named, typed values.
    Decode(commands::decode::Args),
    /// Decode a bus passively, live or from a candump log: filters by node and parameter, a
    /// trigger with a window of frames before and after it; table, CSV or JSON lines.
    Trace(commands::trace::Args),
    /// Export a description's PDOs as a DBC file for CAN log tools (cantools, SavvyCAN).
    Dbc(commands::dbc::Args),
    /// Export a description as a CiA 306 EDS, or import a vendor EDS as a TOML overlay.
    Eds(commands::eds::Args),
    /// Find the CANopen nodes or Modbus units on a bus and match their identity against descriptions.
    Scan(commands::scan::Args),
    /// LSS (CiA 305): find CANopen nodes without a node id (Fastscan), set node ids and bit rates.
    Lss(commands::lss::Args),
    /// Many CANopen nodes on one bus: boot them from a network file, or list their status.
    Network(commands::network::Args),
    /// CANopen Safety: the safety configuration signature of an SRDO.
    Safety(commands::safety::Args),
    /// Save a drive's configuration to a file, write it back, or compare it (exit code 0: done
    /// or equal, 1: different, 2: error).
    Config(commands::config::Args),
    /// Expose drives to an MQTT broker: values retained with their units, writes from clients
    /// through the checks of `write` (docs/gateway.md).
    Gateway(commands::gateway::Args),
}

fn main() -> ExitCode {
    let command = Cli::parse().command;
    // `config` tells a difference (1) from a failure (2), as diff(1) does.
    let failure = match command {
        Command::Config(_) => ExitCode::from(2),
        _ => ExitCode::FAILURE,
    };
    let result = match command {
        Command::Check(args) => commands::check::run(args),
        Command::Dump(args) => commands::dump::run(args),
        Command::Diff(args) => commands::diff::run(args),
        Command::New(args) => commands::new::run(args),
        Command::Generate(args) => commands::generate::run(args),
        Command::Sim(args) => commands::sim::run(args),
        Command::Read(args) => commands::read::run(args),
        Command::Write(args) => commands::write::run(args),
        Command::Watch(args) => commands::watch::run(args),
        Command::Decode(args) => commands::decode::run(args),
        Command::Dbc(args) => commands::dbc::run(args),
        Command::Trace(args) => commands::trace::run(args),
        Command::Eds(args) => commands::eds::run(args),
        Command::Safety(args) => commands::safety::run(args),
        Command::Scan(args) => commands::scan::run(args),
        Command::Config(args) => commands::config::run(args),
        Command::Lss(args) => commands::lss::run(args),
        Command::Network(args) => commands::network::run(args),
        Command::Gateway(args) => commands::gateway::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error::CliError::Differs(count)) => {
            eprintln!("{count} difference(s)");
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("error: {e}");
            failure
        }
    }
}

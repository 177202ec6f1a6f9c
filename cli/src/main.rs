//! The `drivegen` command-line tool.

use std::path::PathBuf;
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
    Check {
        /// Description file, or a folder with a device.toml.
        description: PathBuf,
    },
    /// Print the normalized device model.
    Dump {
        /// Description file, or a folder with a device.toml.
        description: PathBuf,
        /// Print JSON (the schema of docs/ir-json.md).
        #[arg(long)]
        json: bool,
    },
    /// Generate the Rust source of a drive crate into a folder.
    Generate {
        /// Description file, or a folder with a device.toml.
        description: PathBuf,
        /// Output folder; receives drive.rs.
        #[arg(long)]
        out: PathBuf,
    },
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::Check { description } => check(&description),
        Command::Dump { description, json } => dump(&description, json),
        Command::Generate { description, out } => generate(description, out),
    }
}

/// Checks a description, printing diagnostics to stderr; the device if valid.
fn load(description: &std::path::Path) -> Option<drivegen::ir::Device> {
    let checked = drivegen::check(description);
    if !checked.diagnostics.is_empty() {
        eprintln!("{}", checked.render());
    }
    checked.device
}

fn check(description: &std::path::Path) -> ExitCode {
    match load(description) {
        Some(device) => {
            println!(
                "{}: {} parameters, {} enums, {} flags types — ok",
                device.device.name,
                device.parameters.len(),
                device.enums.len(),
                device.flags.len()
            );
            ExitCode::SUCCESS
        }
        None => ExitCode::FAILURE,
    }
}

fn dump(description: &std::path::Path, json: bool) -> ExitCode {
    let Some(device) = load(description) else {
        return ExitCode::FAILURE;
    };
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&device).expect("the IR serializes")
        );
    } else {
        for p in &device.parameters {
            println!(
                "{:<32} {:<8} {}",
                p.name,
                p.data_type.name(),
                p.unit.as_deref().unwrap_or("")
            );
        }
    }
    ExitCode::SUCCESS
}

fn generate(description: PathBuf, out: PathBuf) -> ExitCode {
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("cannot create {}: {e}", out.display());
        return ExitCode::FAILURE;
    }
    match drivegen::Builder::new(description)
        .out_dir(&out)
        .emit_rerun_if_changed(false)
        .compile()
    {
        Ok(path) => {
            println!("wrote {}", path.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}

//! The `poinav` command line: make building models (IFC) robot-ready.

mod enrich;
mod inspect;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Make building models (IFC) robot-ready.
#[derive(Debug, Parser)]
#[command(name = "poinav", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Summarise an IFC file: schema, unit, storeys, counts per class, spaces, doors, diagnostics.
    Inspect(inspect::Args),
    /// Add robot POI semantics (three property sets) to a copy of an IFC file; write CSV and IDS.
    Enrich(enrich::Args),
}

/// Exit code for unreadable input, or diagnostics under `--strict`.
pub const EXIT_BAD_INPUT: u8 = 2;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Inspect(args) => inspect::run(&args),
        Command::Enrich(args) => enrich::run(&args),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(EXIT_BAD_INPUT)
        }
    }
}

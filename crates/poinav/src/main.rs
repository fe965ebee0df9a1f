//! The `poinav` command line: make building models (IFC) robot-ready.

mod author;
mod demo;
mod enrich;
mod export;
mod inspect;
mod navigate;
mod plan;
mod serve;
mod simulate;

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
    /// Find a route between two rooms for a robot profile (A* on the occupancy grid, POI-aware costs).
    Route(navigate::RouteArgs),
    /// Accessibility audit per robot profile: doors, transitions, reachable spaces, drawings.
    Audit(navigate::AuditArgs),
    /// Draw a storey's floor plan as SVG: walls with door gaps, doors coloured by accessibility,
    /// spaces with names, scale bar.
    Plan(plan::Args),
    /// Export the model in other formats: 3D (GLB, FBX).
    #[command(subcommand)]
    Export(export::Export),
    /// Run a simulation scenario (robots with 5-ray sensors, Algorithm 1); exit 1 when an expectation fails.
    Simulate(simulate::Args),
    /// The main job end to end: test building, enrichment, the paper's three scenarios, design
    /// iteration, 3D export and an HTML report.
    Demo(demo::Args),
    /// Start the browser viewer: the building in 3D and live robots driven with the keyboard
    /// (Robot1: arrow keys, Robot2: W A S D), POI colours, events, trace playback, VR.
    Serve(serve::Args),
    /// Write the paper's test building (IFC4X3_ADD2): a corridor with rooms on both sides.
    DemoBuilding(author::DemoBuildingArgs),
    /// Change a model for design iteration, losslessly otherwise.
    #[command(subcommand)]
    Patch(author::Patch),
}

/// `#id: message` for a problem of instance `id`, without repeating the id when the message
/// already starts with it.
pub fn with_id(id: impl std::fmt::Display, message: impl std::fmt::Display) -> String {
    let (id, message) = (id.to_string(), message.to_string());
    if message.starts_with(&format!("{id}:")) {
        message
    } else {
        format!("{id}: {message}")
    }
}

/// Exit code for unreadable input, or diagnostics under `--strict`.
pub const EXIT_BAD_INPUT: u8 = 2;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Inspect(args) => inspect::run(&args),
        Command::Enrich(args) => enrich::run(&args),
        Command::Plan(args) => plan::run(&args),
        Command::Route(args) => navigate::route(&args),
        Command::Audit(args) => navigate::audit(&args),
        Command::Export(export) => export::run(&export),
        Command::Simulate(args) => simulate::run(&args),
        Command::Demo(args) => demo::run(&args),
        Command::Serve(args) => serve::run(&args),
        Command::DemoBuilding(args) => author::demo_building(&args),
        Command::Patch(author::Patch::DoorWidth(args)) => author::door_width(&args),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(EXIT_BAD_INPUT)
        }
    }
}

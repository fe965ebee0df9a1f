//! The `poinav` command line: make building models (IFC) robot-ready.

/// `println!` for command output. When standard output is closed (`poinav inspect x | head -1`)
/// the process ends quietly with exit code 0 instead of panicking: whatever reads the output
/// has seen all it wanted, and output files are complete by the time anything is printed.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::stdout_line(format_args!($($arg)*))
    };
}

/// `eprintln!` for messages: a closed standard error is ignored.
macro_rules! errln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

mod author;
mod demo;
mod enrich;
mod export;
mod inspect;
mod navigate;
mod plan;
mod progress;
mod record;
mod serve;
mod simulate;
mod warnings;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Make building models (IFC) robot-ready.
#[derive(Debug, Parser)]
#[command(name = "poinav", version, about, after_help = EXIT_CODES)]
struct Cli {
    #[command(flatten)]
    flags: Flags,
    #[command(subcommand)]
    command: Command,
}

/// Options every command takes: what is printed on standard error besides errors.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct Flags {
    /// Print nothing on standard error but errors: no progress bars, no warnings.
    #[arg(short, long, global = true)]
    pub quiet: bool,
    /// List every warning, instead of one line per kind of warning with a count.
    #[arg(short, long, global = true, conflicts_with = "quiet")]
    pub verbose: bool,
    /// Print the wall time of each stage (reading, meshing, sectioning, rasterising, graph,
    /// simulation, writing) on standard error at the end.
    #[arg(long, global = true)]
    pub timings: bool,
    /// Write outputs even when the model gave no geometry at all (else: exit 2).
    #[arg(long, global = true)]
    pub allow_empty: bool,
}

static FLAGS: std::sync::OnceLock<Flags> = std::sync::OnceLock::new();

/// The global flags of this run.
pub fn flags() -> Flags {
    FLAGS.get().copied().unwrap_or_default()
}

/// Refuses a model that gave no geometry at all (nothing meshed), unless `--allow-empty`:
/// its outputs would be empty drawings, maps and scenes that look like an empty building.
pub fn ensure_geometry(file: &std::path::Path, meshed: usize, failed: usize) -> anyhow::Result<()> {
    if meshed > 0 || flags().allow_empty {
        return Ok(());
    }
    anyhow::bail!(
        "no geometry in {}: none of its elements could be meshed ({} failed); nothing to draw or navigate (--allow-empty writes the outputs anyway)",
        file.display(),
        warnings::thousands(failed)
    )
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
    /// Export the model in other formats: 3D (GLB, FBX) and Nav2 maps per storey.
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

/// Writes one line to standard output; ends the process (exit 0) when nobody reads it any more.
pub fn stdout_line(args: std::fmt::Arguments<'_>) {
    use std::io::Write as _;
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_fmt(args).and_then(|()| out.write_all(b"\n")) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
    }
}

/// The robot profile at `path`, else the paper's robot.
pub fn profile(path: Option<&std::path::Path>) -> anyhow::Result<poinav_poi::RobotProfile> {
    Ok(match path {
        Some(p) => poinav_poi::RobotProfile::load(p)?,
        None => poinav_poi::RobotProfile::paper(),
    })
}

/// The default POI rules, extended by the rule file at `path` when given.
pub fn rules(path: Option<&std::path::Path>) -> anyhow::Result<poinav_poi::RuleSet> {
    Ok(match path {
        Some(p) => poinav_poi::RuleSet::with_user_file(p)?,
        None => poinav_poi::RuleSet::defaults(),
    })
}

/// True when `e` comes from writing to a closed pipe.
fn broken_pipe(e: &anyhow::Error) -> bool {
    use std::io::ErrorKind::BrokenPipe;
    e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == BrokenPipe)
            || c.downcast_ref::<serde_json::Error>()
                .is_some_and(|j| j.io_error_kind() == Some(BrokenPipe))
    })
}

/// `e` and its causes joined by `: `, leaving out a cause whose text the message already ends
/// with (errors that name their source in their own message, as `cannot write x: {source}`).
pub fn error_text(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for link in e.chain() {
        let part = link.to_string();
        if text.ends_with(&part) {
            continue;
        }
        if !text.is_empty() {
            text.push_str(": ");
        }
        text.push_str(&part);
    }
    text
}

/// The exit codes, for `--help` (the README has the same table).
const EXIT_CODES: &str = "Exit codes:
  0  done (the route exists, every required space is reachable, every expectation held)
  1  the answer is no: no route (unreachable, or no room for the robot), an
     `audit --require-reachable` space not reachable, a `simulate` expectation failed
  2  bad input: a file that cannot be read, an unknown or ambiguous space or storey name,
     an option out of range, an output that cannot be written, `inspect --strict` with
     diagnostics";

/// Exit code for unreadable input, or diagnostics under `--strict`.
pub const EXIT_BAD_INPUT: u8 = 2;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let _ = FLAGS.set(cli.flags);
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
    progress::finish();
    match result {
        Ok(code) => code,
        // The reader of our standard output stopped early: not an error of ours.
        Err(e) if broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            errln!("error: {}", error_text(&e));
            ExitCode::from(EXIT_BAD_INPUT)
        }
    }
}

//! Writing a run's outputs: `DIR/trace.jsonl` (streamed while the run goes, or from memory),
//! `DIR/summary.json` and the SVG plots, each atomically. (The write-back of what the sensors
//! found into a copy of the IFC is `poinav_bridge::write_back`.)

use std::path::{Path, PathBuf};

use poinav_nav::Floor;

use crate::error::SimError;
use crate::plot;
use crate::recorder::{TraceFormat, TraceOut};
use crate::run::{run_with, Outcome};
use crate::scenario::Scenario;
use poinav_io::AtomicFile;

fn io(path: &Path, e: std::io::Error) -> SimError {
    SimError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// Writes trace.jsonl (when the outcome kept its trace in memory, see [`crate::run()`]),
/// summary.json, trajectories.svg, speed.svg and distance.svg into `dir` (created if missing);
/// returns the paths written.
pub fn write_outputs(
    dir: &Path,
    outcome: &Outcome,
    floor: &Floor,
) -> Result<Vec<PathBuf>, SimError> {
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut written = Vec::new();
    if let Some(trace) = &outcome.trace {
        let path = dir.join(TRACE);
        poinav_io::write_atomic(&path, trace).map_err(|e| io(&path, e))?;
        written.push(path);
    }
    written.extend(write_summary_and_plots(dir, outcome, floor)?);
    Ok(written)
}

/// The trace's file name in an output folder.
pub const TRACE: &str = "trace.jsonl";

/// The compact trace's file name in an output folder ([`crate::trace_bin`]).
pub const TRACE_BIN: &str = "trace.bin";

/// Removes `path` if it exists (a trace an earlier run left).
fn remove_stale(path: &Path) -> Result<(), SimError> {
    match std::fs::remove_file(path) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(io(path, e)),
    }
}

fn write_summary_and_plots(
    dir: &Path,
    outcome: &Outcome,
    floor: &Floor,
) -> Result<Vec<PathBuf>, SimError> {
    let mut summary = serde_json::to_string_pretty(&outcome.summary()).expect("summary is JSON");
    summary.push('\n');
    let files = [
        ("summary.json", summary),
        ("trajectories.svg", plot::trajectories(outcome, floor)),
        ("speed.svg", plot::speed(outcome)),
        ("distance.svg", plot::distance(outcome, floor)),
    ];
    let mut written = Vec::new();
    for (name, text) in files {
        let path = dir.join(name);
        poinav_io::write_atomic(&path, text.as_bytes()).map_err(|e| io(&path, e))?;
        written.push(path);
    }
    Ok(written)
}

/// Runs `scenario` (its variant `variant`) on `floor` and writes its outputs into `dir`
/// (created if missing): the trace streamed to `DIR/trace.jsonl` as the steps are taken
/// (every `trace_every`-th step; `None`: no trace, and a trace.jsonl left by an earlier run is
/// removed so it cannot be mistaken for this one's), published atomically at the end, then
/// summary.json and the plots. Memory does not grow with the run's length (but for its events).
pub fn run_into(
    dir: &Path,
    scenario: &Scenario,
    variant: Option<&str>,
    floor: &Floor,
    trace_every: Option<u64>,
) -> Result<(Outcome, Vec<PathBuf>), SimError> {
    run_into_as(
        dir,
        scenario,
        variant,
        floor,
        trace_every,
        TraceFormat::Jsonl,
    )
}

/// [`run_into`] writing the trace in `format`: `DIR/trace.jsonl` or `DIR/trace.bin`
/// ([`TRACE_BIN`]); a trace of the other format left by an earlier run is removed.
pub fn run_into_as(
    dir: &Path,
    scenario: &Scenario,
    variant: Option<&str>,
    floor: &Floor,
    trace_every: Option<u64>,
    format: TraceFormat,
) -> Result<(Outcome, Vec<PathBuf>), SimError> {
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let (name, other) = match format {
        TraceFormat::Jsonl => (TRACE, TRACE_BIN),
        TraceFormat::Bin => (TRACE_BIN, TRACE),
    };
    remove_stale(&dir.join(other))?;
    let path = dir.join(name);
    let mut written = Vec::new();
    let outcome = match trace_every {
        Some(every) => {
            let mut file = AtomicFile::create(&path).map_err(|e| io(&path, e))?;
            let out = TraceOut {
                writer: &mut file,
                every,
                name: path.display().to_string(),
                format,
            };
            let outcome = run_with(scenario, variant, floor, Some(out))?;
            file.commit().map_err(|e| io(&path, e))?;
            written.push(path);
            outcome
        }
        None => {
            let outcome = run_with(scenario, variant, floor, None)?;
            remove_stale(&path)?;
            outcome
        }
    };
    written.extend(write_summary_and_plots(dir, &outcome, floor)?);
    Ok((outcome, written))
}

//! `poinav simulate SCENARIO -o DIR`: runs every variant (or one) of a scenario file, writes
//! the trace as it goes (thinned with `--trace-every N`, none with `--no-trace`, compact with
//! `--trace-format bin`), then summary and plots; optionally writes what the robots found back into the IFC.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use poinav_bridge::Prepared;
use poinav_sim::{Outcome, Scenario};

/// Arguments of `poinav simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The scenario file (TOML, see docs/scenarios.md).
    scenario: PathBuf,
    /// Output folder: trace.jsonl, summary.json, trajectories.svg, speed.svg, distance.svg
    /// (one sub-folder per variant when the scenario has variants).
    #[arg(short, long)]
    output: PathBuf,
    /// Run only this variant.
    #[arg(long)]
    variant: Option<String>,
    /// Write the sensor findings (conditional roles, SENSOR_BASED statuses) into a copy of the
    /// building's IFC here (with several variants: one file per variant, `NAME.<variant>.ifc`).
    #[arg(long)]
    write_back: Option<PathBuf>,
    /// Keep every N-th step in trace.jsonl (1: every step). The trace is written as the run
    /// goes; summary, expectations and plots use every step whatever N is.
    #[arg(long, value_name = "N", default_value_t = 1,
          value_parser = clap::value_parser!(u64).range(1..))]
    trace_every: u64,
    /// Write no trace.jsonl (summary, expectations and plots are the same as with one).
    #[arg(long, conflicts_with = "trace_every")]
    no_trace: bool,
    /// The trace's format: `jsonl` (trace.jsonl, what every reader takes) or `bin`
    /// (trace.bin: fixed-size binary records, about a quarter of the bytes and a small part of
    /// the time to write; `poinav_sim::trace_bin::read_lines` gives back the JSON Lines, and
    /// `--mcap` and Python's `poinav.read_trace` read it too; the viewer's playback reads
    /// trace.jsonl only).
    #[arg(
        long,
        value_name = "FORMAT",
        default_value = "jsonl",
        conflicts_with = "no_trace"
    )]
    trace_format: TraceFormatArg,
    /// Also write a ROS 2 recording (MCAP: scans, odometry, TF, map, POI markers and events)
    /// of the trace's steps here (with several variants: `NAME.<variant>.mcap`).
    #[arg(long, value_name = "FILE", conflicts_with = "no_trace")]
    mcap: Option<PathBuf>,
}

/// `--trace-format`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TraceFormatArg {
    /// JSON Lines (trace.jsonl).
    Jsonl,
    /// Compact binary records (trace.bin).
    Bin,
}

/// Writes the ROS 2 recording of `run` (its trace in `format`, floor and Nav2 map) to `path`.
fn write_mcap(
    scenario: &Scenario,
    run: &VariantRun,
    format: poinav_sim::TraceFormat,
    path: &Path,
) -> anyhow::Result<()> {
    let profile = poinav_sim::scenario::load_profile(&scenario.building.profile, &scenario.dir)?;
    let options = poinav_nav::Nav2Options::default();
    let map = poinav_mcap::storey_map(run.building.floor(), &profile, &options)?;
    let scene = poinav_mcap::Scene {
        floor: run.building.floor(),
        profile: &profile,
        map: &map,
        dt: scenario.dt,
    };
    let summary = match format {
        poinav_sim::TraceFormat::Jsonl => {
            let trace = run.dir.join(poinav_sim::output::TRACE);
            poinav_mcap::write_recording(&trace, &scene, path)?
        }
        poinav_sim::TraceFormat::Bin => {
            // The compact trace read as the JSON Lines it stands for.
            let trace = run.dir.join(poinav_sim::output::TRACE_BIN);
            let open = || -> Result<Box<dyn std::io::BufRead>, std::io::Error> {
                let lines =
                    poinav_sim::trace_bin::read_file(&trace).map_err(std::io::Error::other)?;
                Ok(Box::new(lines.into_jsonl()))
            };
            poinav_mcap::write_recording_from(&open, &trace, &scene, path)?
        }
    };
    outln!(
        "wrote ROS 2 recording to {} ({} steps, {} messages)",
        path.display(),
        summary.steps,
        summary.total()
    );
    Ok(())
}

/// One variant's result.
pub struct VariantRun {
    /// Variant name, if the scenario has variants.
    pub variant: Option<String>,
    /// Output folder.
    pub dir: PathBuf,
    /// The run.
    pub outcome: Outcome,
    /// The building it ran on.
    pub building: Prepared,
}

/// Runs `variant` (or every variant) of `scenario`, writing outputs under `out` (the whole
/// trace).
pub fn run_scenario(
    scenario: &Scenario,
    only: Option<&str>,
    out: &Path,
) -> anyhow::Result<Vec<VariantRun>> {
    run_scenario_with(scenario, only, out, Some(1))
}

/// [`run_scenario`] with the trace thinned to every `trace_every`-th step, or none.
pub fn run_scenario_with(
    scenario: &Scenario,
    only: Option<&str>,
    out: &Path,
    trace_every: Option<u64>,
) -> anyhow::Result<Vec<VariantRun>> {
    run_scenario_as(
        scenario,
        only,
        out,
        trace_every,
        poinav_sim::TraceFormat::Jsonl,
    )
}

/// [`run_scenario_with`] writing the trace in `format`.
pub fn run_scenario_as(
    scenario: &Scenario,
    only: Option<&str>,
    out: &Path,
    trace_every: Option<u64>,
    format: poinav_sim::TraceFormat,
) -> anyhow::Result<Vec<VariantRun>> {
    let names: Vec<Option<String>> = match only {
        Some(v) => vec![Some(v.to_string())],
        None if scenario.variant_names().is_empty() => vec![None],
        None => scenario
            .variant_names()
            .into_iter()
            .map(|v| Some(v.to_string()))
            .collect(),
    };
    let mut runs = Vec::new();
    for variant in names {
        crate::progress::stage("preparing");
        let building = poinav_bridge::prepare(scenario, variant.as_deref())?;
        crate::warnings::print(&crate::warnings::of_building(
            &building.model,
            &building.dropped,
            &building.uncut,
            &building.building,
        ));
        let dir = match &variant {
            Some(v) => out.join(v),
            None => out.to_path_buf(),
        };
        crate::progress::stage("simulation");
        let (outcome, _) = poinav_sim::run_into_as(
            &dir,
            scenario,
            variant.as_deref(),
            building.floor(),
            trace_every,
            format,
        )?;
        crate::progress::end();
        runs.push(VariantRun {
            variant,
            dir,
            outcome,
            building,
        });
    }
    Ok(runs)
}

/// Prints one line per expectation; returns whether all held.
pub fn report(name: &str, runs: &[VariantRun]) -> bool {
    let mut all = true;
    for r in runs {
        let label = match &r.variant {
            Some(v) => format!("{name} [{v}]"),
            None => name.to_string(),
        };
        for j in &r.outcome.judged {
            outln!(
                "  {label:<28} {:<22} {}  measured {}",
                j.kind,
                if j.pass { "PASS" } else { "FAIL" },
                j.measured
            );
        }
        all &= r.outcome.passed();
    }
    all
}

/// Runs `poinav simulate`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let scenario = Scenario::load(&args.scenario)?;
    let trace_every = (!args.no_trace).then_some(args.trace_every);
    let format = match args.trace_format {
        TraceFormatArg::Jsonl => poinav_sim::TraceFormat::Jsonl,
        TraceFormatArg::Bin => poinav_sim::TraceFormat::Bin,
    };
    let runs = run_scenario_as(
        &scenario,
        args.variant.as_deref(),
        &args.output,
        trace_every,
        format,
    )?;
    let passed = report(&scenario.name, &runs);
    if let Some(target) = &args.write_back {
        let stamp =
            poinav_ifc::timestamp::iso8601_utc(poinav_ifc::timestamp::now_or_source_date_epoch());
        let opts = poinav_poi::WriteOptions {
            prefix: "Pset_".into(),
            timestamp: stamp,
        };
        for r in &runs {
            let path = match (&r.variant, runs.len()) {
                (Some(v), n) if n > 1 => target.with_extension(format!("{v}.ifc")),
                _ => target.clone(),
            };
            let editor = poinav_bridge::write_back(
                &r.building.model,
                &r.building.classification,
                &r.outcome,
                &opts,
            )?;
            editor
                .write(&path)
                .with_context(|| format!("writing {}", path.display()))?;
            outln!("wrote sensor findings to {}", path.display());
        }
    }
    if let Some(target) = &args.mcap {
        for r in &runs {
            let path = match (&r.variant, runs.len()) {
                (Some(v), n) if n > 1 => target.with_extension(format!("{v}.mcap")),
                _ => target.clone(),
            };
            write_mcap(&scenario, r, format, &path)?;
        }
    }
    outln!("outputs in {}", args.output.display());
    Ok(if passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

//! `poinav inspect`: what an IFC file contains, as text or JSON.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use poinav_ifc::{spatial, units, Diagnostic, Model};
use serde::Serialize;

/// Arguments of `poinav inspect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The IFC file to read (never modified).
    file: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Exit with code 2 when the file has any diagnostic.
    #[arg(long)]
    strict: bool,
}

#[derive(Debug, Serialize)]
struct StoreyRow {
    id: u64,
    guid: Option<String>,
    name: Option<String>,
    elevation_m: Option<f64>,
}

#[derive(Debug, Serialize)]
struct SpaceRow {
    id: u64,
    guid: Option<String>,
    name: Option<String>,
    long_name: Option<String>,
    storey: Option<String>,
    storey_id: Option<u64>,
}

#[derive(Debug, Serialize)]
struct DoorRow {
    id: u64,
    guid: Option<String>,
    name: Option<String>,
    storey: Option<String>,
    storey_id: Option<u64>,
    overall_width_m: Option<f64>,
    overall_height_m: Option<f64>,
}

#[derive(Debug, Serialize)]
struct DiagnosticRow {
    kind: &'static str,
    id: Option<u64>,
    line: Option<usize>,
    message: String,
}

#[derive(Debug, Serialize)]
struct Report {
    file: String,
    schema: &'static str,
    schema_identifier: String,
    length_unit: String,
    length_unit_m: f64,
    instances: usize,
    counts: BTreeMap<&'static str, usize>,
    storeys: Vec<StoreyRow>,
    spaces: Vec<SpaceRow>,
    doors: Vec<DoorRow>,
    diagnostics: usize,
    diagnostic_list: Vec<DiagnosticRow>,
}

fn report(model: &Model) -> Report {
    let unit = units::length_unit(model);
    let structure = spatial::spatial_structure(model, &unit);
    let storey_names: BTreeMap<_, _> = structure
        .storeys
        .iter()
        .map(|s| (s.id, s.name.clone()))
        .collect();
    let doors = model
        .instances_of("IfcDoor")
        .into_iter()
        .map(|d| DoorRow {
            id: d.id().0,
            guid: d.global_id(),
            name: d.name(),
            storey: spatial::storey_of(d).and_then(|s| s.name()),
            storey_id: spatial::storey_of(d).map(|s| s.id().0),
            overall_width_m: d.get_f64("OverallWidth").map(|w| unit.to_metres(w)),
            overall_height_m: d.get_f64("OverallHeight").map(|h| unit.to_metres(h)),
        })
        .collect();
    let mut diagnostics: Vec<Diagnostic> = model.diagnostics().to_vec();
    if !unit.declared {
        diagnostics.push(Diagnostic {
            kind: poinav_ifc::DiagnosticKind::MissingUnit,
            id: structure.project,
            line: None,
            message: "no length unit declared; metres assumed".into(),
        });
    }
    Report {
        file: model.file().display().to_string(),
        schema: model.schema().name(),
        schema_identifier: model.header().schema_identifier.clone(),
        length_unit: unit.name.clone(),
        length_unit_m: unit.metres_per_unit,
        instances: model.len(),
        counts: model.type_counts(),
        storeys: structure
            .storeys
            .iter()
            .map(|s| StoreyRow {
                id: s.id.0,
                guid: s.global_id.clone(),
                name: s.name.clone(),
                elevation_m: s.elevation_m,
            })
            .collect(),
        spaces: structure
            .spaces
            .iter()
            .map(|s| SpaceRow {
                id: s.id.0,
                guid: s.global_id.clone(),
                name: s.name.clone(),
                long_name: s.long_name.clone(),
                storey: s
                    .storey
                    .and_then(|id| storey_names.get(&id).cloned().flatten()),
                storey_id: s.storey.map(|id| id.0),
            })
            .collect(),
        doors,
        diagnostics: diagnostics.len(),
        diagnostic_list: diagnostics
            .iter()
            .map(|d| DiagnosticRow {
                kind: d.kind.code(),
                id: d.id.map(|i| i.0),
                line: d.line,
                message: d.message.clone(),
            })
            .collect(),
    }
}

const SUMMARY_CLASSES: [&str; 12] = [
    "IfcBuildingStorey",
    "IfcSpace",
    "IfcWall",
    "IfcDoor",
    "IfcWindow",
    "IfcSlab",
    "IfcStair",
    "IfcRamp",
    "IfcColumn",
    "IfcFurnishingElement",
    "IfcOpeningElement",
    "IfcProduct",
];

fn print_text(r: &Report, out: &mut impl Write) -> std::io::Result<()> {
    writeln!(out, "{}", r.file)?;
    writeln!(
        out,
        "  schema       {} (as written: {})",
        r.schema, r.schema_identifier
    )?;
    writeln!(
        out,
        "  length unit  {} = {} m",
        r.length_unit, r.length_unit_m
    )?;
    writeln!(out, "  instances    {}", r.instances)?;
    writeln!(out, "storeys ({})", r.storeys.len())?;
    for s in &r.storeys {
        let elev = s
            .elevation_m
            .map_or("?".to_string(), |e| format!("{e:.3} m"));
        writeln!(
            out,
            "  {:>10}  {}  #{}",
            elev,
            s.name.as_deref().unwrap_or("(unnamed)"),
            s.id
        )?;
    }
    writeln!(out, "counts (subtypes included)")?;
    for c in SUMMARY_CLASSES {
        if let Some(n) = r.counts.get(c) {
            writeln!(out, "  {c:<22}{n:>8}")?;
        }
    }
    writeln!(out, "spaces ({})", r.spaces.len())?;
    for s in &r.spaces {
        writeln!(
            out,
            "  {:<12} {:<28} storey {}",
            s.name.as_deref().unwrap_or("-"),
            s.long_name.as_deref().unwrap_or("-"),
            s.storey.as_deref().unwrap_or("-")
        )?;
    }
    writeln!(out, "doors ({})", r.doors.len())?;
    for d in &r.doors {
        let w = d
            .overall_width_m
            .map_or("?".to_string(), |w| format!("{w:.3}"));
        let h = d
            .overall_height_m
            .map_or("?".to_string(), |h| format!("{h:.3}"));
        writeln!(
            out,
            "  {} {:>7} x {:>6} m  {}  storey {}",
            d.guid.as_deref().unwrap_or("-"),
            w,
            h,
            d.name.as_deref().unwrap_or("-"),
            d.storey.as_deref().unwrap_or("-")
        )?;
    }
    writeln!(out, "diagnostics ({})", r.diagnostics)?;
    for d in &r.diagnostic_list {
        let line = d.line.map(|l| format!("line {l}: ")).unwrap_or_default();
        let id = d.id.map(|i| format!("#{i}: ")).unwrap_or_default();
        writeln!(out, "  {line}{id}{} ({})", d.message, d.kind)?;
    }
    Ok(())
}

/// Runs `poinav inspect`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let model = Model::open(&args.file)?;
    let r = report(&model);
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    if args.json {
        serde_json::to_writer_pretty(&mut out, &r).context("writing JSON")?;
        writeln!(out)?;
    } else {
        print_text(&r, &mut out)?;
    }
    out.flush()?;
    if args.strict && r.diagnostics > 0 {
        errln!(
            "error: {} diagnostics in {} (--strict)",
            r.diagnostics,
            args.file.display()
        );
        return Ok(ExitCode::from(crate::EXIT_BAD_INPUT));
    }
    Ok(ExitCode::SUCCESS)
}

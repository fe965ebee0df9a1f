//! Writing a run's outputs: `DIR/trace.jsonl`, `DIR/summary.json` and the SVG plots, each
//! atomically; and the write-back of what the sensors found into a copy of the IFC through
//! `poinav_poi::runtime::apply` and `poinav_poi::write_enrichment`.

use std::path::{Path, PathBuf};

use poinav_ifc::{Editor, Model};
use poinav_nav::Floor;
use poinav_poi::runtime::{self, Observation};
use poinav_poi::{Classification, WriteOptions};

use crate::error::SimError;
use crate::plot;
use crate::run::Outcome;

fn io(path: &Path, e: std::io::Error) -> SimError {
    SimError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// Writes trace.jsonl, summary.json, trajectories.svg, speed.svg and distance.svg into `dir`
/// (created if missing); returns the paths written.
pub fn write_outputs(
    dir: &Path,
    outcome: &Outcome,
    floor: &Floor,
) -> Result<Vec<PathBuf>, SimError> {
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut summary = serde_json::to_string_pretty(&outcome.summary()).expect("summary is JSON");
    summary.push('\n');
    let files = [
        ("trace.jsonl", outcome.trace_jsonl()),
        ("summary.json", summary),
        ("trajectories.svg", plot::trajectories(outcome, floor)),
        ("speed.svg", plot::speed(outcome)),
        ("distance.svg", plot::distance(outcome, floor)),
    ];
    let mut written = Vec::new();
    for (name, text) in files {
        let path = dir.join(name);
        poinav_ifc::output::write_atomic(&path, text.as_bytes()).map_err(|e| io(&path, e))?;
        written.push(path);
    }
    Ok(written)
}

/// The enrichment `classification` of `model` with the run's findings applied (rule R5, in the
/// order observed): each door's last sensor clearance decides its B-2 and AccessibilityStatus
/// (ValidationMethod SENSOR_BASED); a zone where robots came closer than its
/// MinInterRobotSeparation keeps C-2 (a run that ends with the robots apart still records that
/// they interacted there).
pub fn apply_findings(classification: &Classification, outcome: &Outcome) -> Classification {
    let mut c = classification.clone();
    for (gid, observation, _) in &outcome.data.observations {
        let Some(el) = c.elements.iter_mut().find(|e| &e.global_id == gid) else {
            continue;
        };
        if let Observation::RobotDistance { distance_m } = observation {
            let close = el
                .coordination
                .as_ref()
                .is_some_and(|k| *distance_m < k.min_separation_m);
            if !close {
                continue;
            }
        }
        runtime::apply(el, *observation);
    }
    c
}

/// An editor holding `model` with the findings written (`opts.timestamp` is LastValidated);
/// write it with `Editor::write`.
pub fn write_back<'m>(
    model: &'m Model,
    classification: &Classification,
    outcome: &Outcome,
    opts: &WriteOptions,
) -> Result<Editor<'m>, SimError> {
    let c = apply_findings(classification, outcome);
    Ok(poinav_poi::write_enrichment(model, &c, opts)?)
}

//! What `poinav inspect --json` reports, as a JSON value: schema, unit, counts, storeys,
//! spaces, doors (widths in metres) and diagnostics. The same library calls as the CLI's
//! `inspect.rs`; the Python tests compare the two outputs key by key.

use std::collections::BTreeMap;

use poinav_ifc::{spatial, units, Diagnostic, DiagnosticKind, Model};
use serde_json::{json, Value};

/// Doors: id, GlobalId, Name, storey, overall width and height in metres.
pub fn doors(model: &Model) -> Vec<Value> {
    let unit = units::length_unit(model);
    model
        .instances_of("IfcDoor")
        .into_iter()
        .map(|d| {
            let storey = spatial::storey_of(d);
            json!({
                "id": d.id().0,
                "guid": d.global_id(),
                "name": d.name(),
                "storey": storey.and_then(|s| s.name()),
                "storey_id": storey.map(|s| s.id().0),
                "overall_width_m": d.get_f64("OverallWidth").map(|w| unit.to_metres(w)),
                "overall_height_m": d.get_f64("OverallHeight").map(|h| unit.to_metres(h)),
            })
        })
        .collect()
}

/// Storeys sorted by elevation: id, GlobalId, Name, elevation in metres.
pub fn storeys(model: &Model) -> Vec<Value> {
    let unit = units::length_unit(model);
    spatial::spatial_structure(model, &unit)
        .storeys
        .iter()
        .map(|s| json!({"id": s.id.0, "guid": s.global_id, "name": s.name, "elevation_m": s.elevation_m}))
        .collect()
}

/// The whole report.
pub fn report(model: &Model) -> Value {
    let unit = units::length_unit(model);
    let structure = spatial::spatial_structure(model, &unit);
    let storey_names: BTreeMap<_, _> = structure
        .storeys
        .iter()
        .map(|s| (s.id, s.name.clone()))
        .collect();
    let mut diagnostics: Vec<Diagnostic> = model.diagnostics().to_vec();
    if !unit.declared {
        diagnostics.push(Diagnostic {
            kind: DiagnosticKind::MissingUnit,
            id: structure.project,
            line: None,
            message: "no length unit declared; metres assumed".into(),
        });
    }
    let spaces: Vec<Value> = structure
        .spaces
        .iter()
        .map(|s| {
            json!({
                "id": s.id.0,
                "guid": s.global_id,
                "name": s.name,
                "long_name": s.long_name,
                "storey": s.storey.and_then(|id| storey_names.get(&id).cloned().flatten()),
                "storey_id": s.storey.map(|id| id.0),
            })
        })
        .collect();
    let diagnostic_list: Vec<Value> = diagnostics
        .iter()
        .map(|d| json!({"kind": d.kind.code(), "id": d.id.map(|i| i.0), "line": d.line, "message": d.message}))
        .collect();
    json!({
        "file": model.file().display().to_string(),
        "schema": model.schema().name(),
        "schema_identifier": model.header().schema_identifier,
        "length_unit": unit.name,
        "length_unit_m": unit.metres_per_unit,
        "instances": model.len(),
        "counts": model.type_counts(),
        "storeys": storeys(model),
        "spaces": spaces,
        "doors": doors(model),
        "diagnostics": diagnostics.len(),
        "diagnostic_list": diagnostic_list,
    })
}

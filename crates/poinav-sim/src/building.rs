//! Preparing a scenario's building: generate the paper's test building or read the IFC file,
//! apply the design patches (`poinav patch door-width`), enrich it (classification with the
//! rules and profile) and turn the storey into a [`Floor`]. The IFC -> Floor step for arbitrary
//! files is the caller's (poinav-nav's `Floor::from_plan`); the test building has its own.

use poinav_ifc::Model;
use poinav_nav::Floor;
use poinav_poi::{classify, Classification, RuleSet};

use crate::demo_floor::demo_floor;
use crate::error::SimError;
use crate::scenario::{load_profile, Scenario};

/// Time stamp written into generated and patched IFC headers (keeps runs reproducible).
pub const STAMP: &str = "1970-01-01T00:00:00";

/// Turns an enriched model's storey (by name; `None`: the first) into a floor.
pub type FloorFromModel<'a> =
    &'a dyn Fn(&Model, &Classification, Option<&str>) -> Result<Floor, String>;

/// A building ready to simulate on.
#[derive(Debug)]
pub struct Prepared {
    /// The IFC after the patches (what a write-back edits).
    pub model: Model,
    /// Its enrichment.
    pub classification: Classification,
    /// The storey as a floor.
    pub floor: Floor,
    /// What the patches did, in words.
    pub notes: Vec<String>,
}

/// Prepares the building of `scenario` for `variant`; `convert` turns IFC files (not the test
/// building) into floors.
pub fn prepare(
    scenario: &Scenario,
    variant: Option<&str>,
    convert: Option<FloorFromModel<'_>>,
) -> Result<Prepared, SimError> {
    let v = scenario.variant(variant)?;
    let b = &scenario.building;
    let building_err = |m: String| SimError::Building(m);
    let mut bytes = match (&b.demo, &b.ifc) {
        (Some(demo), _) => poinav_author::demo_building(&demo.building(), STAMP)
            .map_err(|e| building_err(e.to_string()))?,
        (None, Some(path)) => {
            let p = scenario.resolve(path);
            std::fs::read(&p).map_err(|e| SimError::Io {
                path: p.display().to_string(),
                message: e.to_string(),
            })?
        }
        (None, None) => return Err(building_err("no building".into())),
    };
    let name = b
        .ifc
        .clone()
        .unwrap_or_else(|| "poinav-demo-building.ifc".into());
    let read =
        |bytes: Vec<u8>| Model::from_bytes(&name, bytes).map_err(|e| building_err(e.to_string()));
    let mut notes = Vec::new();
    for patch in b
        .patches
        .iter()
        .chain(v.iter().flat_map(|v| v.patches.iter()))
    {
        let model = read(bytes)?;
        let (editor, done) =
            poinav_author::patch_door_width(&model, &patch.door, patch.width_m, STAMP)
                .map_err(|e| building_err(format!("patch door `{}`: {e}", patch.door)))?;
        notes.push(format!(
            "door `{}` ({}) width {:?} -> {} m",
            patch.door, done.global_id, done.old_width_m, done.new_width_m
        ));
        notes.extend(done.warnings);
        bytes = editor.to_bytes();
    }
    let model = read(bytes)?;
    let profile = load_profile(&b.profile, &scenario.dir).map_err(building_err)?;
    let rules = match &b.rules {
        None => RuleSet::defaults(),
        Some(r) => RuleSet::with_user_file(&scenario.resolve(r))?,
    };
    let classification = classify(&model, &rules, &profile);
    let floor = match (&b.demo, convert) {
        (Some(demo), _) => demo_floor(&demo.building(), &model, &classification)?,
        (None, Some(f)) => f(&model, &classification, b.storey.as_deref()).map_err(building_err)?,
        (None, None) => {
            return Err(building_err(
                "an IFC building needs a storey -> floor converter (poinav-nav); only the test building (`demo`) is built in".into(),
            ))
        }
    };
    Ok(Prepared {
        model,
        classification,
        floor,
        notes,
    })
}

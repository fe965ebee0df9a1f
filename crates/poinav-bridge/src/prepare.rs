//! Preparing a scenario's building: generate the paper's test building or read the IFC file,
//! apply the design patches (`poinav patch door-width`), enrich it (classification with the
//! rules and profile) and make its [`Building`] ([`crate::building`]; the test building from
//! its layout, [`crate::demo_floor`]). `poinav simulate` and `poinav serve --scenario` both
//! run on what this prepared.

use poinav_geom::{GeomError, ModelMeshes};
use poinav_ifc::{EntityId, Model};
use poinav_nav::{Building, Floor};
use poinav_poi::{classify, Classification, RuleSet};
use poinav_sim::scenario::{load_profile, Scenario};

use crate::building::{building, Stages};
use crate::demo_floor::{demo_floor, demo_spec};
use crate::dropped::Dropped;
use crate::error::BridgeError;
use crate::ifc_floor::{pick, StoreyKey};

/// Time stamp written into generated and patched IFC headers (keeps runs reproducible).
pub const STAMP: &str = "1970-01-01T00:00:00";

/// A building ready to simulate on.
#[derive(Debug)]
pub struct Prepared {
    /// The IFC after the patches (what a write-back edits).
    pub model: Model,
    /// Its enrichment.
    pub classification: Classification,
    /// Every storey as a floor (the test building: its one floor).
    pub building: Building,
    /// Each floor's storey, in the same order.
    pub storeys: Vec<StoreyKey>,
    /// The floor the scenario's robots drive on: its `storey`, else the lowest with doors.
    pub current: usize,
    /// What the building left out, and why.
    pub dropped: Vec<Dropped>,
    /// The elements meshed without an opening or boolean operand that could not be made
    /// ([`ModelMeshes::uncut`]; none for the test building).
    pub uncut: Vec<(EntityId, GeomError)>,
    /// What the patches did, in words.
    pub notes: Vec<String>,
}

impl Prepared {
    /// The floor the scenario's robots drive on.
    pub fn floor(&self) -> &Floor {
        &self.building.floors[self.current]
    }
}

/// Prepares the building of `scenario` for `variant`.
pub fn prepare(scenario: &Scenario, variant: Option<&str>) -> Result<Prepared, BridgeError> {
    prepare_keeping(scenario, variant, false).map(|(p, _)| p)
}

/// Like [`prepare`], and hands back the element meshes the building was made from (none for
/// the test building, whose floor comes from its layout), for a caller that shows them too
/// (`poinav serve --scenario`) and would otherwise mesh the model a second time.
pub fn prepare_with_meshes(
    scenario: &Scenario,
    variant: Option<&str>,
) -> Result<(Prepared, Option<ModelMeshes>), BridgeError> {
    prepare_keeping(scenario, variant, true)
}

fn prepare_keeping(
    scenario: &Scenario,
    variant: Option<&str>,
    keep_meshes: bool,
) -> Result<(Prepared, Option<ModelMeshes>), BridgeError> {
    let v = scenario.variant(variant)?;
    let b = &scenario.building;
    let mut bytes = match (&b.demo, &b.ifc) {
        (Some(demo), _) => {
            poinav_author::demo_building(&demo_spec(demo), STAMP).map_err(BridgeError::Generate)?
        }
        (None, Some(path)) => {
            let p = scenario.resolve(path);
            std::fs::read(&p).map_err(|source| BridgeError::Io {
                path: p.display().to_string(),
                source,
            })?
        }
        (None, None) => return Err(BridgeError::NoBuilding),
    };
    let name = b
        .ifc
        .clone()
        .unwrap_or_else(|| "poinav-demo-building.ifc".into());
    let read = |bytes: Vec<u8>| Model::from_bytes(&name, bytes).map_err(BridgeError::Read);
    let mut notes = Vec::new();
    for patch in b
        .patches
        .iter()
        .chain(v.iter().flat_map(|v| v.patches.iter()))
    {
        let model = read(bytes)?;
        let (editor, done) =
            poinav_author::patch_door_width(&model, &patch.door, patch.width_m, STAMP).map_err(
                |source| BridgeError::Patch {
                    door: patch.door.clone(),
                    source,
                },
            )?;
        notes.push(format!(
            "door `{}` ({}) width {:?} -> {} m",
            patch.door, done.global_id, done.old_width_m, done.new_width_m
        ));
        notes.extend(done.warnings);
        bytes = editor.to_bytes();
    }
    let model = read(bytes)?;
    let profile = load_profile(&b.profile, &scenario.dir)?;
    let rules = match &b.rules {
        None => RuleSet::defaults(),
        Some(r) => RuleSet::with_user_file(&scenario.resolve(r))?,
    };
    let classification = classify(&model, &rules, &profile);
    let (building, storeys, dropped, uncut, meshes) = match &b.demo {
        Some(demo) => {
            let floor = demo_floor(&demo_spec(demo), &model, &classification)?;
            let key = StoreyKey {
                name: Some(floor.name.clone()),
                global_id: None,
                label: floor.name.clone(),
                has_doors: !floor.doors.is_empty(),
            };
            (
                Building::single(floor),
                vec![key],
                Vec::new(),
                Vec::new(),
                None,
            )
        }
        None => {
            let mut stages = Stages::of(&model);
            let made = building(&model, &classification, &stages);
            let uncut = if keep_meshes {
                stages.meshes.uncut.clone()
            } else {
                std::mem::take(&mut stages.meshes.uncut)
            };
            let meshes = keep_meshes.then_some(stages.meshes);
            (made.building, made.storeys, made.dropped, uncut, meshes)
        }
    };
    // The test building has one storey, whatever the scenario names.
    let current = match &b.demo {
        Some(_) => 0,
        None => pick(&storeys, b.storey.as_deref())?,
    };
    let prepared = Prepared {
        model,
        classification,
        building,
        storeys,
        current,
        dropped,
        uncut,
        notes,
    };
    Ok((prepared, meshes))
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use poinav_sim::Scenario;

    /// The simulator's unit tests run on these floors of the test building (it cannot prepare
    /// them itself); they must be what [`super::prepare`] makes, byte for byte as JSON.
    /// `POINAV_BLESS=1` rewrites them.
    #[test]
    fn sim_fixtures_are_what_prepare_makes() {
        let sim = Path::new(env!("CARGO_MANIFEST_DIR")).join("../poinav-sim");
        let doors = Scenario::from_toml(
            "name = \"doors\"\nduration_s = 1.0\n[building]\ndemo = { rooms_per_side = 3 }\n[[robot]]\nname = \"R\"\nstart = { x = 1.0, y = 1.0 }\ncontroller = { kind = \"idle\" }\n",
            "doors.toml",
            Path::new("."),
        )
        .unwrap();
        let shipped = |f: &str| Scenario::load(&sim.join("scenarios").join(f)).unwrap();
        let cases = [
            (doors, None, "doors.floor.json"),
            (
                shipped("doorway.toml"),
                Some("door-0.80"),
                "doorway-door-0.80.floor.json",
            ),
            (shipped("yield.toml"), None, "yield.floor.json"),
        ];
        for (scenario, variant, file) in cases {
            let floor = super::prepare(&scenario, variant).unwrap().floor().clone();
            let mut json = serde_json::to_string_pretty(&floor).unwrap();
            json.push('\n');
            let path = sim.join("testdata").join(file);
            if std::env::var_os("POINAV_BLESS").is_some() {
                std::fs::write(&path, &json).unwrap();
            }
            let kept = std::fs::read_to_string(&path).unwrap_or_default();
            assert!(
                kept == json,
                "{} is not what prepare makes; rerun with POINAV_BLESS=1",
                path.display()
            );
            assert_eq!(floor.doors.len(), 2 * scenario_rooms(&scenario));
        }
    }

    fn scenario_rooms(s: &Scenario) -> usize {
        s.building
            .demo
            .as_ref()
            .and_then(|d| d.rooms_per_side)
            .unwrap_or(poinav_author::DemoBuilding::default().rooms_per_side)
    }
}

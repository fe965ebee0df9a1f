//! The one function from an IFC model to a [`Building`]: every storey's plan as a floor (roles,
//! statuses, the spaces each door joins), the stairs, ramps and lifts that connect the storeys
//! with their shadows on the storeys they rise to, each storey's level, and the doors above
//! ground level that open onto the terrain; with what was left out and why.

use poinav_geom::floor_level::LevelFrom;
use poinav_geom::{floor_plans_with_meshes, mesh_model, FloorPlan, ModelMeshes, PlanOptions};
use poinav_ifc::Model;
use poinav_nav::{Building, Floor, FloorLevel, LevelSource};
use poinav_poi::Classification;

use crate::dropped::{Dropped, DroppedKind};
use crate::ifc_floor::{door_space_boundaries, floor_from_plan, StoreyKey};
use crate::terrain::{mark_terrain_doors, terrain_of};
use crate::vertical::vertical_connections;

/// The stages a building is made from: the model's element meshes and its storeys' floor plans
/// (one floor per plan, in their order). Callers that time or report those stages, or cut plans
/// with other options, make them themselves; [`Stages::of`] makes them with the defaults.
#[derive(Debug)]
pub struct Stages {
    /// Element meshes (`poinav_geom::mesh_model`).
    pub meshes: ModelMeshes,
    /// Storey floor plans from those meshes.
    pub plans: Vec<FloorPlan>,
}

impl Stages {
    /// The meshes of `model` and its storeys' plans with the default options.
    pub fn of(model: &Model) -> Stages {
        let meshes = mesh_model(model);
        let plans = floor_plans_with_meshes(model, &meshes, &PlanOptions::default());
        Stages { meshes, plans }
    }
}

/// A building made from a model, and what was left out of it.
#[derive(Debug, Clone)]
pub struct Bridged {
    /// The building: one floor per storey plan.
    pub building: Building,
    /// Each floor's storey (same order), for picking one by name ([`crate::pick`]).
    pub storeys: Vec<StoreyKey>,
    /// Stairs, ramps and lifts connecting nothing; terrain bodies that cannot be meshed.
    pub dropped: Vec<Dropped>,
}

/// The building of `model` classified by `classification`, from `stages`: every storey as a
/// floor (storeys without doors or spaces included; each door with the spaces its
/// `IfcRelSpaceBoundary`s name), the stairs, ramps and lifts between them
/// ([`crate::vertical`]) and, when a storey is not at ground level, the doors that open onto
/// the terrain ([`crate::terrain`]).
pub fn building(model: &Model, classification: &Classification, stages: &Stages) -> Bridged {
    let Stages { meshes, plans } = stages;
    let boundaries = door_space_boundaries(model);
    let mut floors: Vec<Floor> = plans
        .iter()
        .map(|p| floor_from_plan(p, classification, &boundaries))
        .collect();
    let clearance = (classification.profile.width_m / 2.0).max(0.25);
    let vertical = vertical_connections(model, meshes, &floors, clearance);
    let levels = floor_levels(plans, &floors);
    // A stair's or ramp's shadow is in the way on every storey it rises to, not only the one
    // it stands on (a drop where the floor slab has no hole modelled).
    for (floor, obstacle) in vertical.shadows {
        floors[floor].obstacles.push(obstacle);
    }
    let mut dropped = vertical.dropped;
    // Doors above (or below) ground level that open onto the terrain are entrances too.
    if levels.iter().any(|l| !l.at_ground) {
        let terrain = terrain_of(model, meshes);
        for (site, e) in &terrain.failures {
            let entity = model.entity(*site);
            dropped.push(Dropped {
                id: entity
                    .and_then(|s| s.global_id())
                    .unwrap_or_else(|| site.to_string()),
                name: entity.and_then(|s| s.name()),
                kind: DroppedKind::Terrain,
                reason: e.to_string(),
            });
        }
        mark_terrain_doors(model, meshes, plans, &mut floors, &levels, &terrain);
    }
    Bridged {
        building: Building {
            floors,
            connections: vertical.connections,
            levels,
        },
        storeys: plans.iter().map(StoreyKey::of).collect(),
        dropped,
    }
}

/// Each storey's level from its plan: the storey's elevation, the walking level and where it
/// comes from, and whether it is at ground level ([`poinav_nav::level::ground_levels`]: the
/// storeys with spaces or doors decide).
fn floor_levels(plans: &[FloorPlan], floors: &[Floor]) -> Vec<FloorLevel> {
    let used: Vec<(f64, bool)> = floors
        .iter()
        .map(|f| (f.elevation_m, !f.zones.is_empty() || !f.doors.is_empty()))
        .collect();
    let ground = poinav_nav::level::ground_levels(&used);
    plans
        .iter()
        .zip(ground)
        .map(|(p, at_ground)| FloorLevel {
            storey_elevation_m: p.storey_elevation_m,
            walking_level_m: p.elevation_m,
            from: match p.level_from {
                LevelFrom::StoreyElevation => LevelSource::StoreyElevation,
                LevelFrom::FloorSlabs => LevelSource::FloorSlabs,
                LevelFrom::Spaces => LevelSource::Spaces,
            },
            at_ground,
        })
        .collect()
}

//! IFC storey -> `poinav_nav::Floor`: a storey floor plan (`poinav-geom`) with the roles,
//! statuses and coordination of a POI classification, and the spaces each door bounds from
//! `IfcRelSpaceBoundary` where the model has them, for simulating and navigating real
//! buildings.

use std::collections::{BTreeMap, HashMap};

use poinav_geom::floor_level::LevelFrom;
use poinav_geom::{
    floor_plans, floor_plans_with_meshes, mesh_model, FloorPlan, ModelMeshes, PlanItemKind,
    PlanOptions, PlanSource,
};
use poinav_ifc::Model;
use poinav_nav::{Floor, FloorDoor, FloorObstacle, FloorZone, LevelSource, ObstacleKind};
use poinav_poi::{AccessibilityStatus, Classification, Classified, Role};

use crate::vertical::{vertical_connections, Dropped};

/// The converter the simulator calls for IFC buildings: the storey named `storey` (or the
/// lowest storey with doors) as a [`Floor`].
pub fn converter() -> impl Fn(&Model, &Classification, Option<&str>) -> Result<Floor, String> {
    |model, classification, storey| {
        let plans = floor_plans(model, &PlanOptions::default());
        let plan = pick(&plans, storey)?;
        let mut floor = floor_from_plan(plan, classification);
        apply_space_boundaries(&mut floor, &door_space_boundaries(model));
        Ok(floor)
    }
}

/// The plan of the storey named `storey`, else the lowest one with doors, else the first.
pub fn pick<'p>(plans: &'p [FloorPlan], storey: Option<&str>) -> Result<&'p FloorPlan, String> {
    match storey {
        Some(name) => plans
            .iter()
            .find(|p| {
                p.storey_name.as_deref() == Some(name)
                    || p.storey_global_id.as_deref() == Some(name)
            })
            .ok_or_else(|| {
                let names: Vec<String> = plans
                    .iter()
                    .map(|p| {
                        p.storey_name
                            .clone()
                            .unwrap_or_else(|| p.storey.to_string())
                    })
                    .collect();
                format!(
                    "no storey named `{name}`; the model has: {}",
                    names.join(", ")
                )
            }),
        None => plans
            .iter()
            .find(|p| !p.doors.is_empty())
            .or(plans.first())
            .ok_or_else(|| "the model has no storey to plan".to_string()),
    }
}

fn roles(c: Option<&Classified>) -> Vec<Role> {
    let mut r: Vec<Role> = c
        .map(|c| c.primary.iter().chain(&c.conditional).copied().collect())
        .unwrap_or_default();
    r.sort();
    r.dedup();
    r
}

/// One storey plan with the roles, statuses and coordination of `classification`.
pub fn floor_from_plan(plan: &FloorPlan, classification: &Classification) -> Floor {
    let by_guid: HashMap<&str, &Classified> = classification
        .elements
        .iter()
        .map(|c| (c.global_id.as_str(), c))
        .collect();
    let required = classification.profile.min_clearance_width();
    let mut floor = Floor {
        name: plan
            .storey_name
            .clone()
            .unwrap_or_else(|| plan.storey.to_string()),
        elevation_m: plan.elevation_m,
        ..Floor::default()
    };
    for item in &plan.items {
        let c = by_guid.get(item.global_id.as_str()).copied();
        let rings = || {
            item.regions
                .iter()
                .map(|r| r.outer.clone())
                .filter(|r| r.len() >= 3)
                .collect::<Vec<_>>()
        };
        let kind = match item.kind {
            // Only bounded (its section reached a bound): unknown, never free.
            k if item.source == PlanSource::Outline
                && (k.is_obstacle() || matches!(k, PlanItemKind::Stair | PlanItemKind::Ramp)) =>
            {
                ObstacleKind::Unknown
            }
            PlanItemKind::Wall
            | PlanItemKind::Column
            | PlanItemKind::Obstacle
            | PlanItemKind::DoorFrame
            | PlanItemKind::Window => ObstacleKind::Structure,
            PlanItemKind::Furniture => ObstacleKind::Furniture,
            PlanItemKind::Stair | PlanItemKind::Ramp => ObstacleKind::Transition,
            PlanItemKind::Space => {
                for region in &item.regions {
                    floor.zones.push(FloorZone {
                        id: item.global_id.clone(),
                        name: item.name.clone(),
                        long_name: item.long_name.clone(),
                        ring: region.outer.clone(),
                        roles: roles(c),
                        coordination: c
                            .and_then(|c| c.coordination.as_ref())
                            .map(|k| (k.min_separation_m, k.protocol)),
                    });
                }
                continue;
            }
            // Door leaves are passages or closures depending on the status: navigation decides
            // from the door's passage ring; the simulator treats doors as open.
            PlanItemKind::DoorLeaf | PlanItemKind::DoorOpening => continue,
        };
        let rings = rings();
        if !rings.is_empty() {
            floor.obstacles.push(FloorObstacle {
                id: item.global_id.clone(),
                class: item.class.clone(),
                kind,
                rings,
                roles: roles(c),
            });
        }
    }
    for door in &plan.doors {
        let Some(ring) = door.passage().map(|r| r.outer) else {
            continue;
        };
        let c = by_guid.get(door.global_id.as_str()).copied();
        let access = c.and_then(|c| c.accessibility.as_ref());
        floor.doors.push(FloorDoor {
            id: door.global_id.clone(),
            name: door.name.clone(),
            ring,
            center: door.center,
            clear_width_m: door.clear_width_m,
            status: access.map_or(AccessibilityStatus::PendingValidation, |a| a.status),
            min_clearance_width_m: access.map_or(required, |a| a.min_clearance_width_m),
            roles: roles(c),
            spaces: None,
            doorless: false,
            terrain: false,
        });
    }
    // Doorways (openings no door fills): open whatever the model says, as wide as they are.
    for opening in &plan.openings {
        let Some(ring) = opening.passage().map(|r| r.outer) else {
            continue;
        };
        let c = by_guid.get(opening.global_id.as_str()).copied();
        let (status, _) =
            poinav_nav::building::width_status(opening.clear_width_m, &classification.profile);
        floor.doors.push(FloorDoor {
            id: opening.global_id.clone(),
            name: Some(
                opening
                    .name
                    .clone()
                    .unwrap_or_else(|| format!("Doorway {}", opening.door)),
            ),
            ring,
            center: opening.center,
            clear_width_m: opening.clear_width_m,
            status,
            min_clearance_width_m: required,
            roles: roles(c),
            spaces: None,
            doorless: true,
            terrain: false,
        });
    }
    floor
}

/// Per door GlobalId, the GlobalIds of the spaces its `IfcRelSpaceBoundary`s bound (sorted,
/// each once); doors without space boundaries are absent.
pub fn door_space_boundaries(model: &Model) -> BTreeMap<String, Vec<String>> {
    let mut out: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for rel in model.instances_of("IfcRelSpaceBoundary") {
        let (Some(element), Some(space)) = (
            rel.get_ref("RelatedBuildingElement"),
            rel.get_ref("RelatingSpace"),
        ) else {
            continue;
        };
        if !(element.is_a("IfcDoor") || element.is_a("IfcOpeningElement"))
            || !space.is_a("IfcSpace")
        {
            continue;
        }
        let (Some(door), Some(space)) = (element.global_id(), space.global_id()) else {
            continue;
        };
        let spaces = out.entry(door).or_default();
        if let Err(at) = spaces.binary_search(&space) {
            spaces.insert(at, space);
        }
    }
    out
}

/// Gives every door of `floor` found in `boundaries` (from [`door_space_boundaries`]) its
/// spaces, so that the navigation graph joins the spaces the model says it joins.
pub fn apply_space_boundaries(floor: &mut Floor, boundaries: &BTreeMap<String, Vec<String>>) {
    for d in &mut floor.doors {
        if let Some(spaces) = boundaries.get(&d.id) {
            d.spaces = Some(spaces.clone());
        }
    }
}

/// Every storey of `model` as a floor (storeys without doors or spaces included), for
/// navigation: a [`poinav_nav::Building`] with the stairs, ramps and lifts that connect its
/// storeys ([`crate::vertical`]).
pub fn building_of(model: &Model, classification: &Classification) -> poinav_nav::Building {
    building_and_dropped(model, classification).0
}

/// [`building_of`], and the stairs, ramps and lifts left out, with why.
pub fn building_and_dropped(
    model: &Model,
    classification: &Classification,
) -> (poinav_nav::Building, Vec<Dropped>) {
    let meshes = mesh_model(model);
    let plans = floor_plans_with_meshes(model, &meshes, &PlanOptions::default());
    building_from_plans(model, classification, &meshes, &plans)
}

/// [`building_and_dropped`] from the model's meshes and storey plans (default options), for
/// callers that time or report those stages themselves.
pub fn building_from_plans(
    model: &Model,
    classification: &Classification,
    meshes: &ModelMeshes,
    plans: &[FloorPlan],
) -> (poinav_nav::Building, Vec<Dropped>) {
    let boundaries = door_space_boundaries(model);
    let floors: Vec<Floor> = plans
        .iter()
        .map(|p| {
            let mut floor = floor_from_plan(p, classification);
            apply_space_boundaries(&mut floor, &boundaries);
            floor
        })
        .collect();
    let clearance = (classification.profile.width_m / 2.0).max(0.25);
    let vertical = vertical_connections(model, meshes, &floors, clearance);
    let levels = floor_levels(plans, &floors);
    let mut floors = floors;
    // A stair's or ramp's shadow is in the way on every storey it rises to, not only the one
    // it stands on (a drop where the floor slab has no hole modelled).
    for (floor, obstacle) in vertical.shadows {
        floors[floor].obstacles.push(obstacle);
    }
    // Doors above (or below) ground level that open onto the terrain are entrances too.
    if levels.iter().any(|l| !l.at_ground) {
        let terrain = crate::terrain::terrain_of(model, meshes);
        crate::terrain::mark_terrain_doors(model, meshes, plans, &mut floors, &levels, &terrain);
    }
    (
        poinav_nav::Building {
            floors,
            connections: vertical.connections,
            levels,
        },
        vertical.dropped,
    )
}

/// Each storey's level from its plan: the storey's elevation, the walking level and where it
/// comes from, and whether it is at ground level ([`poinav_nav::level::ground_levels`]: the
/// storeys with spaces or doors decide).
pub fn floor_levels(plans: &[FloorPlan], floors: &[Floor]) -> Vec<poinav_nav::FloorLevel> {
    let used: Vec<(f64, bool)> = floors
        .iter()
        .map(|f| (f.elevation_m, !f.zones.is_empty() || !f.doors.is_empty()))
        .collect();
    let ground = poinav_nav::level::ground_levels(&used);
    plans
        .iter()
        .zip(ground)
        .map(|(p, at_ground)| poinav_nav::FloorLevel {
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

//! IFC storey -> `poinav_nav::Floor`: a storey floor plan (`poinav-geom`) with the roles,
//! statuses and coordination of a POI classification, and the spaces each door bounds from
//! `IfcRelSpaceBoundary` where the model has them (decided here once and stored on the door, so
//! the navigation graph does not have to guess them from geometry), obstacles thinner than a
//! grid cell widened to one ([`MIN_OBSTACLE_WIDTH_M`]); and which storey a name picks.

use std::collections::{BTreeMap, HashMap};

use poinav_geom::region;
use poinav_geom::{FloorPlan, PlanItemKind, PlanSource};
use poinav_ifc::Model;
use poinav_nav::{Floor, FloorDoor, FloorObstacle, FloorZone, ObstacleKind};
use poinav_poi::{AccessibilityStatus, Classification, Classified, Role};

use crate::error::BridgeError;

/// Parts of obstacles thinner than this (metres: the navigation grid's default cell,
/// `poinav_nav::GridOptions::resolution_m`) are grown by half of it on each side
/// ([`region::widen_thin`]): a grid samples cells at their centres, and a 5 mm glass panel
/// between two rows of centres would be no obstacle at all.
pub const MIN_OBSTACLE_WIDTH_M: f64 = 0.05;

/// What names a storey: its Name and GlobalId, the label used when it has no Name, and whether
/// its plan has doors.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StoreyKey {
    /// Name.
    pub name: Option<String>,
    /// GlobalId.
    pub global_id: Option<String>,
    /// The Name, else the `#id`.
    pub label: String,
    /// True when its plan has doors.
    pub has_doors: bool,
}

impl StoreyKey {
    /// The key of `plan`'s storey.
    pub fn of(plan: &FloorPlan) -> StoreyKey {
        StoreyKey {
            name: plan.storey_name.clone(),
            global_id: plan.storey_global_id.clone(),
            label: plan
                .storey_name
                .clone()
                .unwrap_or_else(|| plan.storey.to_string()),
            has_doors: !plan.doors.is_empty(),
        }
    }
}

/// The index of the storey named `storey` (Name or GlobalId), else of the lowest one with doors,
/// else the first.
pub fn pick(storeys: &[StoreyKey], storey: Option<&str>) -> Result<usize, BridgeError> {
    match storey {
        Some(name) => storeys
            .iter()
            .position(|s| s.name.as_deref() == Some(name) || s.global_id.as_deref() == Some(name))
            .ok_or_else(|| BridgeError::NoSuchStorey {
                name: name.to_string(),
                storeys: storeys
                    .iter()
                    .map(|s| s.label.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            }),
        None => storeys
            .iter()
            .position(|s| s.has_doors)
            .or((!storeys.is_empty()).then_some(0))
            .ok_or(BridgeError::NoStorey),
    }
}

/// The primary and conditional roles of `c`, sorted, each once.
pub(crate) fn roles(c: Option<&Classified>) -> Vec<Role> {
    let mut r: Vec<Role> = c
        .map(|c| c.primary.iter().chain(&c.conditional).copied().collect())
        .unwrap_or_default();
    r.sort();
    r.dedup();
    r
}

/// One storey plan with the roles, statuses and coordination of `classification`, each door
/// with the spaces `boundaries` gives it.
pub(crate) fn floor_from_plan(
    plan: &FloorPlan,
    classification: &Classification,
    boundaries: &BTreeMap<String, Vec<String>>,
) -> Floor {
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
        // Obstacles at least a grid cell wide, so that no cell centre falls either side of a
        // glass panel or a line and the robot is planned through it.
        let rings = || {
            region::widen_thin(&item.regions, MIN_OBSTACLE_WIDTH_M)
                .into_iter()
                .map(|r| r.outer)
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
            spaces: boundaries.get(&door.global_id).cloned(),
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
            spaces: boundaries.get(&opening.global_id).cloned(),
            doorless: true,
            terrain: false,
        });
    }
    floor
}

/// Per door GlobalId, the GlobalIds of the spaces its `IfcRelSpaceBoundary`s bound (sorted,
/// each once); doors without space boundaries are absent.
pub(crate) fn door_space_boundaries(model: &Model) -> BTreeMap<String, Vec<String>> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn obstacles_are_widened_to_the_default_grid_cell() {
        assert_eq!(
            MIN_OBSTACLE_WIDTH_M,
            poinav_nav::GridOptions::default().resolution_m
        );
    }
}

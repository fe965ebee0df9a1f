//! IFC storey -> `poinav_nav::Floor`: a storey floor plan (`poinav-geom`) with the roles,
//! statuses and coordination of a POI classification, and the spaces each door bounds from
//! `IfcRelSpaceBoundary` where the model has them (decided here once and stored on the door, so
//! the navigation graph does not have to guess them from geometry); and which storey a name
//! picks.

use std::collections::{BTreeMap, HashMap};

use poinav_geom::{FloorPlan, PlanItemKind, PlanSource};
use poinav_ifc::Model;
use poinav_nav::door_status::Block;
use poinav_nav::{ElementId, Floor, FloorDoor, FloorObstacle, FloorZone, ObstacleKind, Ring};
use poinav_poi::{AccessibilityKind, AccessibilityStatus, Classification, Classified, Role};

use crate::error::BridgeError;

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

/// The profile-free facts a door's status is computed from (`poinav_nav::door_status`), as
/// the classification `c` made its verdict: the width its clear-width rule read, or the rule
/// that blocks it and why. A door no rule gave an accessibility has neither (unknown). A door a
/// user's rule judges as stairs or a slope, which no fact of a door holds, is blocked by that
/// rule for every profile when it blocked the classification's, else unknown.
pub(crate) fn door_facts(c: Option<&Classified>) -> (Option<f64>, Option<Block>) {
    let Some((c, a)) = c.and_then(|c| Some((c, c.accessibility.as_ref()?))) else {
        return (None, None);
    };
    let block = || Block {
        rule: c.rule.clone(),
        reason: a.reason.clone(),
    };
    match c.accessibility_kind {
        AccessibilityKind::ClearWidth => (c.facts.clear_width_m, None),
        AccessibilityKind::Blocked => (None, Some(block())),
        _ if a.status == AccessibilityStatus::Blocked => (None, Some(block())),
        _ => (None, None),
    }
}

/// One storey plan with the roles, statuses and coordination of `classification`, each door
/// with the spaces `boundaries` gives it.
pub(crate) fn floor_from_plan(
    plan: &FloorPlan,
    classification: &Classification,
    boundaries: &BTreeMap<String, Vec<ElementId>>,
) -> Floor {
    let by_guid: HashMap<&str, &Classified> = classification
        .elements
        .iter()
        .map(|c| (c.global_id.as_str(), c))
        .collect();
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
                .filter(|r| r.outer.len() >= 3)
                .map(|r| Ring::from(r.outer.clone()))
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
                        id: item.global_id.as_str().into(),
                        name: item.name.clone(),
                        long_name: item.long_name.clone(),
                        ring: region.outer.clone().into(),
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
                id: item.global_id.as_str().into(),
                class: item.class.clone(),
                kind,
                rings,
                roles: roles(c),
            });
        }
    }
    for door in &plan.doors {
        let Some(ring) = door.passage().map(|r| Ring::from(r.outer)) else {
            continue;
        };
        let c = by_guid.get(door.global_id.as_str()).copied();
        let (classified_width_m, blocked) = door_facts(c);
        floor.doors.push(FloorDoor {
            id: door.global_id.as_str().into(),
            name: door.name.clone(),
            ring,
            center: door.center,
            clear_width_m: door.clear_width_m,
            classified_width_m,
            blocked,
            roles: roles(c),
            spaces: boundaries.get(&door.global_id).cloned(),
            doorless: false,
            terrain: false,
        });
    }
    // Doorways (openings no door fills): open whatever the model says, classified by their own
    // width (unknown unless a positive number).
    for opening in &plan.openings {
        let Some(ring) = opening.passage().map(|r| Ring::from(r.outer)) else {
            continue;
        };
        let c = by_guid.get(opening.global_id.as_str()).copied();
        let w = opening.clear_width_m;
        floor.doors.push(FloorDoor {
            id: opening.global_id.as_str().into(),
            name: Some(
                opening
                    .name
                    .clone()
                    .unwrap_or_else(|| format!("Doorway {}", opening.door)),
            ),
            ring,
            center: opening.center,
            clear_width_m: w,
            classified_width_m: (w.is_finite() && w > 0.0).then_some(w),
            blocked: None,
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
pub(crate) fn door_space_boundaries(model: &Model) -> BTreeMap<String, Vec<ElementId>> {
    let mut out: BTreeMap<String, Vec<ElementId>> = BTreeMap::new();
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
        let space = ElementId::from(space);
        if let Err(at) = spaces.binary_search(&space) {
            spaces.insert(at, space);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use poinav_ifc::EntityId;
    use poinav_nav::door_status::{classified_status, door_status};
    use poinav_poi::{
        Accessibility, AccessibilityKind, AccessibilityStatus, Category, Facts, PoiType,
        RobotProfile, ValidationMethod,
    };

    use super::*;

    /// A door classified by `rule` of `kind` with `status` (and `reason`), its facts reading
    /// a clear width of `width`.
    fn classified(
        rule: &str,
        kind: AccessibilityKind,
        status: Option<(AccessibilityStatus, &str)>,
        width: Option<f64>,
    ) -> Classified {
        Classified {
            id: EntityId(7),
            global_id: "1Door000000000000000007".into(),
            class: "IfcDoor".into(),
            name: Some("D7".into()),
            storey: None,
            rule: rule.into(),
            category: Category::Structural,
            poi_type: PoiType::TransitionElement,
            primary: vec![Role::Transition],
            conditional: vec![],
            accessibility_kind: kind,
            accessibility: status.map(|(status, reason)| Accessibility {
                min_clearance_width_m: 0.9,
                min_clearance_height_m: 2.0,
                status,
                method: ValidationMethod::GeometricAnalysis,
                reason: reason.into(),
            }),
            coordination: None,
            facts: Facts {
                clear_width_m: width,
                ..Facts::default()
            },
        }
    }

    fn door(facts: (Option<f64>, Option<Block>)) -> FloorDoor {
        FloorDoor {
            id: "1Door000000000000000007".into(),
            name: None,
            ring: Ring::default(),
            center: glam::DVec2::ZERO,
            clear_width_m: 1.0,
            classified_width_m: facts.0,
            blocked: facts.1,
            roles: vec![],
            spaces: None,
            doorless: false,
            terrain: false,
        }
    }

    #[test]
    fn door_facts_are_what_the_rule_judged() {
        use AccessibilityKind as K;
        use AccessibilityStatus::*;
        let paper = RobotProfile::paper();
        // The clear-width rule: the width it read, nothing blocks.
        let c = classified("R2-door", K::ClearWidth, Some((Restricted, "")), Some(0.8));
        assert_eq!(door_facts(Some(&c)), (Some(0.8), None));
        assert_eq!(
            door_status(&door(door_facts(Some(&c))), &paper).0,
            Restricted
        );
        // A blocking rule: its id and reason, whatever the width.
        let why = "IfcDoor is not passable by a ground robot";
        let c = classified("R-locked", K::Blocked, Some((Blocked, why)), Some(1.2));
        let block = Block {
            rule: "R-locked".into(),
            reason: why.into(),
        };
        assert_eq!(door_facts(Some(&c)), (None, Some(block.clone())));
        assert_eq!(
            classified_status(&door((None, Some(block))), &paper),
            (Blocked, why.into())
        );
        // No accessibility, or no classification: unknown.
        let c = classified("R1", K::None, None, Some(1.2));
        assert_eq!(door_facts(Some(&c)), (None, None));
        assert_eq!(door_facts(None), (None, None));
        // A stairs rule on a door: blocked by it when it blocked, else unknown.
        let c = classified("R-step", K::Stairs, Some((Blocked, "stairs")), Some(1.2));
        assert_eq!(
            door_facts(Some(&c)).1.map(|b| b.rule),
            Some("R-step".into())
        );
        let c = classified("R-step", K::Stairs, Some((FullAccess, "climbs")), Some(1.2));
        assert_eq!(door_facts(Some(&c)), (None, None));
    }
}

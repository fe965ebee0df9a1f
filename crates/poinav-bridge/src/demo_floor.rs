//! The paper's test building as a [`Floor`], built from its `Layout` (walls as rectangles with
//! door gaps, doors as their openings, rooms and the corridor as zones) with GlobalIds, door
//! widths and POI roles read from the generated (and possibly patched and enriched) IFC, so ray
//! hits name real GlobalIds. The one exception to [`crate::building`]: scenarios on the test
//! building keep its exact rectangles (their expectations are measured on them).

use std::collections::BTreeMap;

use glam::DVec2;
use poinav_author::DemoBuilding;
use poinav_ifc::{units, Model};
use poinav_nav::polygon::rect;
use poinav_nav::{Floor, FloorDoor, FloorObstacle, FloorZone, ObstacleKind, Ring};
use poinav_poi::{Classification, Classified};
use poinav_sim::scenario::DemoParams;

use crate::error::BridgeError;
use crate::ifc_floor::{door_facts, roles};

/// The test building `params` describe (unset options keep their defaults).
pub fn demo_spec(params: &DemoParams) -> DemoBuilding {
    let mut b = DemoBuilding::default();
    if let Some(v) = params.rooms_per_side {
        b.rooms_per_side = v;
    }
    if let Some(v) = params.room2_door_width_m {
        b.room2_door_width_m = v;
    }
    if let Some(v) = params.door_width_m {
        b.door_width_m = v;
    }
    if let Some(v) = params.corridor_width_m {
        b.corridor_width_m = v;
    }
    b
}

/// The floor of `spec`'s building as written to `model` (door widths from the model, so a
/// patched door is as wide as the patch made it) with the roles of `classification`.
pub fn demo_floor(
    spec: &DemoBuilding,
    model: &Model,
    classification: &Classification,
) -> Result<Floor, BridgeError> {
    let unit = units::length_unit(model);
    let mut ids: BTreeMap<(&str, String), String> = BTreeMap::new();
    let mut widths: BTreeMap<String, f64> = BTreeMap::new();
    for class in ["IfcWall", "IfcDoor", "IfcSpace"] {
        for e in model.instances_of(class) {
            let (Some(name), Some(gid)) = (e.name(), e.global_id()) else {
                continue;
            };
            if class == "IfcDoor" {
                if let Some(w) = e.get_f64("OverallWidth") {
                    widths.insert(name.clone(), unit.to_metres(w));
                }
            }
            ids.insert((class, name), gid);
        }
    }
    let by_gid: BTreeMap<&str, &Classified> = classification
        .elements
        .iter()
        .map(|c| (c.global_id.as_str(), c))
        .collect();
    let id = |class: &'static str, name: &str| -> Result<String, BridgeError> {
        ids.get(&(class, name.to_string()))
            .cloned()
            .ok_or_else(|| BridgeError::MissingElement {
                class,
                name: name.to_string(),
            })
    };
    let layout = spec.layout();
    let t = spec.wall_thickness_m;
    let (lx, ly) = (spec.length_m(), spec.depth_m());
    let (c0, c1) = (layout.corridor_min[1], layout.corridor_max[1]);
    let mut obstacles = Vec::new();
    let mut wall = |name: &str, rings: Vec<Ring>| -> Result<(), BridgeError> {
        let gid = id("IfcWall", name)?;
        let c = by_gid.get(gid.as_str()).copied();
        obstacles.push(FloorObstacle {
            id: gid.into(),
            class: "IfcWall".into(),
            kind: ObstacleKind::Structure,
            rings,
            roles: roles(c),
        });
        Ok(())
    };
    wall("Exterior wall south", vec![rect(-t, -t, lx + t, 0.0)])?;
    wall("Exterior wall north", vec![rect(-t, ly, lx + t, ly + t)])?;
    wall("Exterior wall west", vec![rect(-t, 0.0, 0.0, ly)])?;
    wall("Exterior wall east", vec![rect(lx, 0.0, lx + t, ly)])?;
    let mut doors = Vec::new();
    for (name, side, y0, y1) in [
        ("Corridor wall south", -1.0, c0 - t, c0),
        ("Corridor wall north", 1.0, c1, c1 + t),
    ] {
        let mut gaps: Vec<(f64, f64)> = Vec::new();
        for room in layout.rooms.iter().filter(|r| r.door.side == side) {
            let w = widths
                .get(&room.door.name)
                .copied()
                .unwrap_or(room.door.width_m);
            let cx = room.door.center[0];
            gaps.push((cx - w / 2.0, cx + w / 2.0));
            let gid = id("IfcDoor", &room.door.name)?;
            let c = by_gid.get(gid.as_str()).copied();
            let clear = c.and_then(|c| c.facts.clear_width_m).unwrap_or(w);
            let (classified_width_m, blocked) = door_facts(c);
            doors.push(FloorDoor {
                id: gid.into(),
                name: Some(room.door.name.clone()),
                ring: rect(cx - w / 2.0, y0, cx + w / 2.0, y1),
                center: DVec2::new(cx, (y0 + y1) / 2.0),
                clear_width_m: clear,
                classified_width_m,
                blocked,
                roles: roles(c),
                spaces: None,
                doorless: false,
                terrain: false,
            });
        }
        gaps.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut rings = Vec::new();
        let mut x = 0.0;
        for (g0, g1) in gaps {
            if g0 > x {
                rings.push(rect(x, y0, g0, y1));
            }
            x = g1;
        }
        if x < lx {
            rings.push(rect(x, y0, lx, y1));
        }
        wall(name, rings)?;
    }
    for i in 1..spec.rooms_per_side {
        let x = i as f64 * (spec.room_width_m + t) - t / 2.0;
        wall(
            &format!("Partition wall south {i}"),
            vec![rect(x - t / 2.0, 0.0, x + t / 2.0, spec.room_depth_m)],
        )?;
        wall(
            &format!("Partition wall north {i}"),
            vec![rect(
                x - t / 2.0,
                c1 + t,
                x + t / 2.0,
                c1 + t + spec.room_depth_m,
            )],
        )?;
    }
    let mut zones = Vec::new();
    let spaces = layout
        .rooms
        .iter()
        .map(|r| (r.name.clone(), r.min, r.max))
        .chain([(
            "Corridor".to_string(),
            layout.corridor_min,
            layout.corridor_max,
        )]);
    for (name, min, max) in spaces {
        let gid = id("IfcSpace", &name)?;
        let c = by_gid.get(gid.as_str()).copied();
        zones.push(FloorZone {
            id: gid.into(),
            name: Some(name.clone()),
            long_name: Some(name),
            ring: rect(min[0], min[1], max[0], max[1]),
            roles: roles(c),
            coordination: c
                .and_then(|c| c.coordination.as_ref())
                .map(|k| (k.min_separation_m, k.protocol)),
        });
    }
    Ok(Floor {
        name: "Ground floor".into(),
        elevation_m: 0.0,
        obstacles,
        doors,
        zones,
    })
}

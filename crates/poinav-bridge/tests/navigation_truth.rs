//! Navigation that tells the truth on multi-storey houses (issue 22, points 1-4), on a house
//! written by IfcOpenShell (`tests/ifcos/author_house.py`: a storey whose elevation is 0.60 m
//! below its slab, a U-shaped stair, a stairwell hole in the upper slab, one-sided space
//! boundaries on the upper floor, a balcony door) and as properties over every corpus model:
//! reachable spaces are joined to reachable ones or an entrance (a lift's own space to a
//! reachable one at its landings), entrances are on the building's outside at ground level
//! (above it only onto the terrain, see `terrain_entrances.rs`), stairs and ramps connect
//! storeys for a legged robot with landings free in the grid and in a zone, and every cell
//! over a hole in a floor slab is occupied (or keepout) in the Nav2 map; and every door's facts
//! give back, for the profile it was classified for, the classification's own verdict.

use std::path::{Path, PathBuf};

use glam::DVec2;
use poinav_bridge::DroppedKind;
use poinav_geom::{floor_plans, PlanOptions, PlanSource};
use poinav_ifc::Model;
use poinav_nav::door_status::classified_status;
use poinav_nav::graph::{zone_at, NodeKind};
use poinav_nav::DoorFrame;
use poinav_nav::{
    audit::audit_profile, Building, CellState, ConnectionKind, Entrance, LevelSource, NavOptions,
    Navigator,
};
use poinav_poi::{classify, AccessibilityStatus, Locomotion, RobotProfile, RuleSet};

fn legged() -> RobotProfile {
    let mut p = RobotProfile::paper();
    p.locomotion = Locomotion::Legged;
    p
}

/// The test house, written into `dir`.
fn house(dir: &Path) -> PathBuf {
    let out = dir.join("house.ifc");
    let py = poinav_testkit::python("ifcopenshell");
    poinav_testkit::ifcos_with(&py, "author_house.py", &[out.as_os_str()]);
    out
}

/// The building of `file` for `profile`, and the stairs and ramps (not lifts) left out. Checks
/// that each door's profile-free facts give back the classification's verdict for `profile`
/// (a doorway's: the clear-width rule on its own width).
fn building(file: &Path, profile: &RobotProfile) -> (Model, Building, Vec<String>) {
    let model = Model::open(file).unwrap();
    let c = classify(&model, &RuleSet::defaults(), profile);
    let made = poinav_bridge::building(&model, &c, &poinav_bridge::Stages::of(&model));
    let (b, dropped) = (made.building, made.dropped);
    for d in b.floors.iter().flat_map(|f| &f.doors) {
        let verdict = match d.doorless {
            true => poinav_nav::building::width_status(d.clear_width_m, profile).0,
            false => c
                .elements
                .iter()
                .find(|e| d.id == e.global_id)
                .and_then(|e| e.accessibility.as_ref())
                .map_or(AccessibilityStatus::PendingValidation, |a| a.status),
        };
        assert_eq!(
            classified_status(d, profile).0,
            verdict,
            "{}: door {} {:?}",
            file.display(),
            d.id,
            d.name
        );
    }
    let dropped = dropped
        .iter()
        .filter(|d| d.kind != DroppedKind::Connection(ConnectionKind::Lift))
        .map(|d| format!("{} {:?}: {}", d.id, d.name, d.reason))
        .collect();
    (model, b, dropped)
}

fn door_named<'a>(nav: &'a Navigator<'_>, name: &str) -> &'a poinav_nav::graph::DoorSides {
    nav.topology
        .doors
        .iter()
        .find(|d| {
            nav.building.floors[d.floor].doors[d.door.get()]
                .name
                .as_deref()
                == Some(name)
        })
        .unwrap_or_else(|| panic!("no door {name}"))
}

fn zone_names(nav: &Navigator<'_>, d: &poinav_nav::graph::DoorSides) -> Vec<String> {
    let mut v: Vec<String> = d
        .zones
        .iter()
        .map(|z| match z {
            Some(z) => nav.building.floors[d.floor].zones[z.get()]
                .name
                .clone()
                .unwrap_or_default(),
            None => "outside".into(),
        })
        .collect();
    v.sort();
    v
}

#[test]
fn the_test_house_tells_the_truth() {
    let dir = tempfile::tempdir().unwrap();
    let file = house(dir.path());
    let profile = legged();
    let (_, b, dropped) = building(&file, &profile);
    assert!(dropped.is_empty(), "{dropped:?}");

    // Storey levels: the ground floor walks on its slab (0.00), not its elevation (-0.60).
    assert_eq!(b.levels.len(), 2);
    let (g, u) = (&b.levels[0], &b.levels[1]);
    assert!((g.storey_elevation_m + 0.6).abs() < 1e-9, "{g:?}");
    assert!(g.walking_level_m.abs() < 1e-9, "{g:?}");
    assert_eq!(g.from, LevelSource::FloorSlabs);
    assert!((u.walking_level_m - 3.0).abs() < 1e-9, "{u:?}");
    assert_eq!(u.from, LevelSource::StoreyElevation);
    assert!(g.at_ground && !u.at_ground);
    assert!(b.floors[0].elevation_m.abs() < 1e-9);

    // The U stair joins the two storeys.
    assert_eq!(b.connections.len(), 1, "{:?}", b.connections);
    let stair = &b.connections[0];
    let on: Vec<usize> = stair.landings.iter().map(|l| l.floor).collect();
    assert_eq!(on, [0, 1]);
    // Landings on the walkable side of the first and last steps (both open south at y = 4.0):
    // the foot in front of flight 1 (x 3.0-4.2), the top in front of flight 2 (x 4.2-5.4),
    // never behind the stair's west wall in the technical room.
    let (foot, top) = (stair.landings[0].point, stair.landings[1].point);
    assert!(
        foot.y < 4.0 - 0.29 && foot.y > 1.5 && (2.9..=4.3).contains(&foot.x),
        "{foot}"
    );
    assert!(
        top.y < 4.0 - 0.29 && top.y > 1.5 && (4.1..=5.5).contains(&top.x),
        "{top}"
    );

    let nav = Navigator::new(&b, &profile, &NavOptions::default()).unwrap();
    for (l, zone) in stair.landings.iter().zip(["Hall", "Landing hall"]) {
        let f = &b.floors[l.floor];
        let z = zone_at(f, l.point).expect("a landing is in a zone");
        assert_eq!(f.zones[z.get()].name.as_deref(), Some(zone));
        let g = &nav.floors[l.floor].grid;
        let i = g.occupancy.cell_of(l.point).unwrap();
        assert_eq!(g.occupancy.cells[i], CellState::Free, "{l:?}");
        assert!(g.traversable(i), "{l:?}");
    }

    // Entrances: the front door only. The upper floor's one-sided boundaries join the rooms
    // behind them, and the balcony door (nothing behind it) is no entrance up there.
    let exterior: Vec<&str> = nav
        .topology
        .doors
        .iter()
        .filter(|d| d.exterior())
        .map(|d| {
            b.floors[d.floor].doors[d.door.get()]
                .name
                .as_deref()
                .unwrap_or("?")
        })
        .collect();
    assert_eq!(exterior, ["Front door"]);
    assert_eq!(
        zone_names(&nav, door_named(&nav, "Bedroom 1 door")),
        ["Bedroom 1", "Landing hall"]
    );
    assert_eq!(
        zone_names(&nav, door_named(&nav, "Bedroom 2 door")),
        ["Bedroom 2", "Landing hall"]
    );
    let balcony = door_named(&nav, "Balcony door");
    assert_eq!(zone_names(&nav, balcony), ["Landing hall", "outside"]);
    assert!(balcony.off_ground && !balcony.exterior());

    // A legged robot reaches every space from the front door; a wheeled one none upstairs.
    let audit = audit_profile(&nav, None).unwrap();
    let unreachable: Vec<_> = audit.spaces.iter().filter(|s| !s.reachable).collect();
    assert!(unreachable.is_empty(), "{unreachable:?}");
    let wheeled = RobotProfile::paper();
    let (_, bw, _) = building(&file, &wheeled);
    let navw = Navigator::new(&bw, &wheeled, &NavOptions::default()).unwrap();
    let audit = audit_profile(&navw, None).unwrap();
    let reach: Vec<(&str, bool)> = audit
        .spaces
        .iter()
        .map(|s| (s.name.as_deref().unwrap_or("?"), s.reachable))
        .collect();
    assert_eq!(
        reach,
        [
            ("Hall", true),
            ("Room", true),
            ("Technical room", true),
            ("Landing hall", false),
            ("Bedroom 1", false),
            ("Bedroom 2", false)
        ]
    );

    // The stairwell (x 3.0-5.4, y 4.0-7.6) is occupied upstairs, never free, for both robots.
    for nav in [&nav, &navw] {
        let g = &nav.floors[1].grid.occupancy;
        let mut cells = 0;
        for i in 0..g.len() {
            let c = g.center(i);
            if c.x > 3.0 && c.x < 5.4 && c.y > 4.0 && c.y < 7.6 {
                cells += 1;
                assert_eq!(g.cells[i], CellState::Occupied, "{c}");
            }
        }
        assert_eq!(cells, 48 * 72);
    }
    let problems = check_properties("test-house", &file, &b, &nav);
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The properties every building must have, for a legged robot's navigator `nav`.
fn check_properties(name: &str, file: &Path, b: &Building, nav: &Navigator<'_>) -> Vec<String> {
    let mut problems = Vec::new();
    let t = &nav.topology;
    let audit = audit_profile(nav, None).unwrap();
    // Reachable spaces: joined to a reachable space or an entrance by a passable door,
    // doorway, open boundary or vertical connection.
    let reachable: Vec<bool> = {
        let mut r = vec![false; t.nodes.len()];
        for s in &audit.spaces {
            if s.reachable {
                let z = b.floors[s.floor]
                    .zones
                    .iter()
                    .position(|z| z.id == s.id)
                    .unwrap();
                r[t.zone_nodes[s.floor][z]] = true;
            }
        }
        r
    };
    for (n, node) in t.nodes.iter().enumerate() {
        if node.kind() != NodeKind::Zone || !reachable[n] {
            continue;
        }
        // A space that is a lift itself is entered at its landings.
        let zone = &b.floors[node.floor].zones[node.zone().unwrap().get()];
        let shaft = b.connections.iter().position(|c| c.id == zone.id);
        let entered = shaft.is_some_and(|ci| {
            t.landing_nodes[ci].iter().any(|&l| {
                nav.open[l]
                    && t.adjacency[l]
                        .iter()
                        .any(|&(_, w)| t.nodes[w].kind() == NodeKind::Zone && reachable[w])
            })
        });
        let joined = entered
            || t.adjacency[n].iter().any(|&(_, v)| {
                if !nav.open[v] {
                    return false;
                }
                match t.nodes[v].kind() {
                    NodeKind::Zone => reachable[v],
                    NodeKind::Door => {
                        let sides = t
                            .door(t.nodes[v].floor, t.nodes[v].door().unwrap())
                            .unwrap();
                        sides.exterior()
                            || t.adjacency[v].iter().any(|&(_, w)| w != n && reachable[w])
                    }
                    NodeKind::Landing => t.landing_nodes[t.nodes[v].connection().unwrap()]
                        .iter()
                        .any(|&l| {
                            l != v
                                && nav.open[l]
                                && t.adjacency[l].iter().any(|&(_, w)| {
                                    t.nodes[w].kind() == NodeKind::Zone && reachable[w]
                                })
                        }),
                }
            });
        if !joined {
            problems.push(format!(
                "{name}: space {} is reachable but joined to nothing reachable",
                node.label()
            ));
        }
    }
    // Entrances: at ground level (or onto the terrain), nothing beyond the outside face, not
    // walled in.
    for d in t.doors.iter().filter(|d| d.exterior()) {
        let floor = &b.floors[d.floor];
        let label = format!("{name}: entrance {:?}", floor.doors[d.door.get()].name);
        let kind = if b.at_ground(d.floor) {
            Entrance::Ground
        } else {
            Entrance::Terrain
        };
        if d.entrance() != Some(kind) {
            problems.push(format!(
                "{label} on storey {} is {:?}, not {kind:?}",
                floor.name,
                d.entrance()
            ));
        }
        if let (Some(f), Some(side)) = (floor.door_frame(d.door.get()), d.outside_side()) {
            let p = f.center + f.normal * side * (f.half_depth + 0.3);
            if zone_at(floor, p).is_some() {
                problems.push(format!("{label} has a space beyond its outside face"));
            }
        }
    }
    // Stairs and ramps: landings free in the grid and in a zone.
    for c in &b.connections {
        for l in &c.landings {
            let floor = &b.floors[l.floor];
            let g = &nav.floors[l.floor].grid.occupancy;
            let free = g
                .cell_of(l.point)
                .is_some_and(|i| g.cells[i] == CellState::Free);
            if !free || zone_at(floor, l.point).is_none() {
                problems.push(format!(
                    "{name}: landing of {} on {} at {} is not free in a zone",
                    c.label(),
                    floor.name,
                    l.point
                ));
            }
        }
    }
    // Holes in floor slabs: occupied or keepout (occupied in the grid is occupied in the map).
    let plans = floor_plans(&Model::open(file).unwrap(), &PlanOptions::default());
    for (fi, plan) in plans.iter().enumerate() {
        let g = &nav.floors[fi].grid.occupancy;
        for item in plan.items.iter().filter(|i| i.source == PlanSource::Void) {
            for r in &item.regions {
                let (lo, hi) = r.bounds();
                for i in 0..g.len() {
                    let c: DVec2 = g.center(i);
                    if c.x < lo.x || c.y < lo.y || c.x > hi.x || c.y > hi.y || !r.contains(c) {
                        continue;
                    }
                    if g.cells[i] != CellState::Occupied {
                        problems.push(format!(
                            "{name}: cell {c} over the hole in {} on {} is {:?}",
                            item.global_id, b.floors[fi].name, g.cells[i]
                        ));
                        break;
                    }
                }
            }
        }
    }
    problems
}

#[test]
fn every_corpus_building_tells_the_truth() {
    let profile = legged();
    let mut problems = Vec::new();
    let mut seen = Vec::new();
    for file in poinav_testkit::corpus() {
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        let (_, b, dropped) = building(&file, &profile);
        if b.floors
            .iter()
            .all(|f| f.doors.is_empty() && f.zones.is_empty())
        {
            continue;
        }
        // Every stair and ramp connects two storeys (a model of one storey has none to join).
        if b.floors.len() > 1 {
            for d in &dropped {
                problems.push(format!("{name}: dropped {d}"));
            }
        }
        let nav = Navigator::new(&b, &profile, &NavOptions::default()).unwrap();
        for c in &b.connections {
            if !poinav_nav::building::passable(c.status(&profile).0, true) {
                problems.push(format!("{name}: {} is closed to a legged robot", c.label()));
            }
        }
        problems.extend(check_properties(&name, &file, &b, &nav));
        seen.push(format!(
            "{name}: {} storeys ({}), {} connections, {} entrances",
            b.floors.len(),
            b.levels
                .iter()
                .map(|l| format!("{:.2} {}", l.walking_level_m, l.from.label()))
                .collect::<Vec<_>>()
                .join(", "),
            b.connections.len(),
            nav.topology.entrances().len()
        ));
    }
    eprintln!("{}", seen.join("\n"));
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

//! Storey floor plans on the corpus and on the paper's test building: every door has a real
//! gap at its clear width, plan contents match the model, the test building's gaps are its
//! door widths.

mod common;

use std::collections::BTreeMap;

use glam::DVec2;
use poinav_geom::door_passage::ClearWidthSource;
use poinav_geom::region::{self, Region};
use poinav_geom::{floor_plans, FloorPlan, FootprintMethod, PlanItemKind, PlanOptions, PlanSource};
use poinav_ifc::{spatial, Model};

/// Half the slack, metres, taken off each side of the clear width before looking for
/// obstacles: the clear width is a nominal attribute and the gap is made by cutting the
/// opening's solid out of the wall's (floating point), so a wall face may lie a hair inside
/// the nominal width. 2 cm in all, far below what a robot's margin is.
const SIDE_SLACK_M: f64 = 0.01;

/// How far beyond the opening's faces the test lines reach, metres.
const BEYOND_M: f64 = 0.02;

/// Lines sampled across the clear width.
const SAMPLES: usize = 9;

/// The obstacle regions of a plan with their bounding boxes.
fn obstacles(plan: &FloorPlan) -> Vec<(&Region, (DVec2, DVec2), &str)> {
    plan.items
        .iter()
        .filter(|i| i.kind.is_obstacle())
        .flat_map(|i| {
            i.regions
                .iter()
                .map(move |r| (r, r.bounds(), i.class.as_str()))
        })
        .collect()
}

/// Why a door has no free passage at its clear width, or `None` when it has.
fn blocked(plan: &FloorPlan, door: &poinav_geom::DoorPassage) -> Option<String> {
    let obstacles = obstacles(plan);
    let half = door.clear_width_m / 2.0 - SIDE_SLACK_M;
    let reach = door.depth_m / 2.0 + BEYOND_M;
    for k in 0..SAMPLES {
        let s = -half + 2.0 * half * k as f64 / (SAMPLES - 1) as f64;
        let a = door.center + door.along * s - door.across * reach;
        let b = door.center + door.along * s + door.across * reach;
        let (lo, hi) = (a.min(b), a.max(b));
        for (r, (rlo, rhi), class) in &obstacles {
            if rhi.x < lo.x || rlo.x > hi.x || rhi.y < lo.y || rlo.y > hi.y {
                continue;
            }
            if r.meets_segment(a, b) {
                return Some(format!(
                    "{class} across the line {s:+.3} m from the centre (clear width {:.3} m)",
                    door.clear_width_m
                ));
            }
        }
    }
    None
}

#[test]
fn every_door_has_a_gap_at_its_clear_width() {
    let mut table = BTreeMap::new();
    let mut failures = Vec::new();
    let mut total = 0;
    for file in common::corpus() {
        let model = Model::open(&file).unwrap();
        if model.count_of("IfcWall") == 0 {
            continue;
        }
        let name = file.file_name().unwrap().to_string_lossy().to_string();
        let plans = floor_plans(&model, &PlanOptions::default());
        let doors = model.instances_of("IfcDoor");
        let mut passed = 0;
        for door in &doors {
            let found = plans
                .iter()
                .find_map(|p| p.doors.iter().find(|d| d.door == door.id()).map(|d| (p, d)));
            match found {
                None => failures.push(format!("{name}: {} has no passage in any plan", door.id())),
                Some((plan, passage)) => match blocked(plan, passage) {
                    Some(why) => failures.push(format!(
                        "{name}: {} {:?} on {:?}: {why}",
                        door.id(),
                        door.name(),
                        plan.storey_name
                    )),
                    None => passed += 1,
                },
            }
        }
        total += doors.len();
        table.insert(name, (passed, doors.len()));
    }
    for (name, (passed, n)) in &table {
        println!("{name}: {passed} / {n} doors have a free passage at their clear width");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_eq!(total, 579, "doors in corpus files with walls");
    let expected = [
        ("duplex-apartment.ifc", 14),
        ("fzk-haus-ifc4.ifc", 5),
        ("fzk-haus-ifc4x3.ifc", 5),
        ("ifc4-test-model.ifc", 2),
        ("ifcopenhouse-ifc4.ifc", 1),
        ("institute-var-2.ifc", 77),
        ("nested-mapped-item.ifc", 7),
        ("office-a.ifc", 102),
        ("revit-japanese-x2.ifc", 1),
        ("schependomlaan-window-frames.ifc", 30),
        ("synthetic-merged-office-duplex-ifc2x3.ifc", 334),
        ("wall-door-column-ifc4x3.ifc", 1),
    ];
    for (name, n) in expected {
        assert_eq!(table.get(name), Some(&(n, n)), "{name}");
    }
}

fn plan_named<'a>(plans: &'a [FloorPlan], storey: &str) -> &'a FloorPlan {
    plans
        .iter()
        .find(|p| p.storey_name.as_deref() == Some(storey))
        .unwrap_or_else(|| panic!("no plan of {storey}"))
}

/// Spaces of `plan`'s storey in the model.
fn spaces_on(model: &Model, plan: &FloorPlan) -> usize {
    model
        .instances_of("IfcSpace")
        .into_iter()
        .filter(|s| spatial::storey_of(*s).map(|st| st.id()) == Some(plan.storey))
        .count()
}

/// Walls of `plan` drawn from an extruded profile ([`FootprintMethod::Outline`]) whose plan
/// area equals their footprint's less the footprints of the openings that span the band
/// (doors, not windows), within 1 cm2: (how many match, how many were compared).
fn walls_match_footprints(model: &Model, plan: &FloorPlan) -> (usize, usize) {
    let mut cache = poinav_geom::PlacementCache::new(model);
    let (mut same, mut of) = (0, 0);
    for wall in model.instances_of("IfcWall") {
        if spatial::storey_of(wall).map(|s| s.id()) != Some(plan.storey) {
            continue;
        }
        let Ok(f) = poinav_geom::footprint_of(&mut cache, wall) else {
            continue;
        };
        if f.method != FootprintMethod::Outline || f.footprint.z_min > plan.band.0 {
            continue;
        }
        let outline = Region::from_ring(f.footprint.polygon).unwrap();
        let cuts: Vec<Region> = poinav_geom::element_mesh::openings_of(wall)
            .into_iter()
            .filter_map(|o| poinav_geom::footprint_of(&mut cache, o).ok())
            .map(|o| o.footprint)
            .filter(|o| o.z_min <= plan.band.0 && o.z_max >= plan.band.1)
            .filter_map(|o| Region::from_ring(o.polygon))
            .collect();
        let expected = region::total_area(&region::difference(&[outline], &cuts));
        let drawn: f64 = plan
            .items
            .iter()
            .filter(|i| i.product == wall.id())
            .map(|i| i.area())
            .sum();
        of += 1;
        if (drawn - expected).abs() < 1e-4 {
            same += 1;
        } else {
            println!(
                "{} {:?}: drawn {drawn:.4} m2, footprint less openings {expected:.4} m2",
                wall.id(),
                wall.name()
            );
        }
    }
    (same, of)
}

/// Spaces of `plan` whose outline encloses the area of their extruded footprint within 1 cm2
/// (the footprint ignores the profile's voids: columns standing in the room, which the plan
/// shows as holes): (matching, compared, spaces with holes).
fn spaces_match_footprints(model: &Model, plan: &FloorPlan) -> (usize, usize, usize) {
    let mut cache = poinav_geom::PlacementCache::new(model);
    let (mut same, mut of, mut holed) = (0, 0, 0);
    for item in plan.items_of(PlanItemKind::Space) {
        let space = model.entity(item.product).unwrap();
        let f = poinav_geom::footprint_of(&mut cache, space).unwrap();
        if f.method != FootprintMethod::Outline {
            continue;
        }
        of += 1;
        let enclosed: f64 = item
            .regions
            .iter()
            .map(|r| poinav_geom::polygon::signed_area(&r.outer))
            .sum();
        holed += usize::from(item.regions.iter().any(|r| !r.holes.is_empty()));
        if (enclosed - f.footprint.area()).abs() < 1e-4 {
            same += 1;
        } else {
            println!(
                "{} {:?}: drawn {enclosed:.4} m2, footprint {:.4} m2",
                space.id(),
                space.name(),
                f.footprint.area()
            );
        }
    }
    (same, of, holed)
}

fn area_of(plan: &FloorPlan, kind: PlanItemKind) -> f64 {
    plan.items_of(kind).map(|i| i.area()).sum()
}

#[test]
fn fzk_haus_ground_floor() {
    let model = Model::open(common::corpus_file("fzk-haus-ifc4.ifc")).unwrap();
    let plans = floor_plans(&model, &PlanOptions::default());
    assert_eq!(plans.len(), 2);
    let eg = plan_named(&plans, "Erdgeschoss");
    assert_eq!(eg.elevation_m, 0.0);
    assert_eq!(eg.band, (0.05, 1.0));
    assert!(eg.problems.is_empty(), "{:?}", eg.problems);
    let spaces = eg.items_of(PlanItemKind::Space).count();
    assert_eq!(spaces, spaces_on(&model, eg));
    assert_eq!(spaces, 6);
    assert_eq!(eg.items_of(PlanItemKind::Wall).count(), 9);
    assert_eq!(eg.doors.len(), 5);
    assert_eq!(eg.items_of(PlanItemKind::DoorOpening).count(), 5);
    // Walls: the same as their extruded footprints less the door openings.
    let (same, of) = walls_match_footprints(&model, eg);
    assert_eq!((same, of), (9, 9));
    // Rooms cover the floor: the spaces add up to their quantities' 101.4 m2.
    assert!((area_of(eg, PlanItemKind::Space) - 101.39).abs() < 0.05);
    // The attic: sloping roof and its members come down into the band.
    let dg = plan_named(&plans, "Dachgeschoss");
    assert_eq!(
        dg.items_of(PlanItemKind::Space).count(),
        spaces_on(&model, dg)
    );
    assert!(dg.elevation_m == 2.7);
}

#[test]
fn office_a_levels() {
    let model = Model::open(common::corpus_file("office-a.ifc")).unwrap();
    let plans = floor_plans(&model, &PlanOptions::default());
    let names: Vec<_> = plans
        .iter()
        .map(|p| p.storey_name.clone().unwrap())
        .collect();
    assert_eq!(names, ["Level 1", "Level 2", "Roof"]);
    for plan in &plans {
        assert!(plan.problems.is_empty(), "{:?}", plan.problems);
        assert_eq!(
            plan.items_of(PlanItemKind::Space).count(),
            spaces_on(&model, plan),
            "{:?}",
            plan.storey_name
        );
        // Every item comes from its mesh.
        assert!(plan.items.iter().all(|i| i.source != PlanSource::Footprint));
    }
    let l1 = &plans[0];
    assert_eq!(l1.items_of(PlanItemKind::Space).count(), 60);
    assert_eq!(l1.doors.len(), 66);
    assert!(l1.items_of(PlanItemKind::Wall).count() > 200);
    let walls = area_of(l1, PlanItemKind::Wall);
    let (lo, hi) = l1.bounds.unwrap();
    println!(
        "Level 1: walls {walls:.1} m2 in a {:.1} x {:.1} m box",
        hi.x - lo.x,
        hi.y - lo.y
    );
    // Walls take a few percent of a plan's floor: 100-150 m2 of walls for 1500 m2 of rooms.
    assert!((100.0..150.0).contains(&walls), "{walls}");
    // Every wall is its footprint less its door openings; every space its footprint, less the
    // columns standing in it.
    assert_eq!(walls_match_footprints(&model, l1), (251, 251));
    assert_eq!(spaces_match_footprints(&model, l1), (60, 60, 4));
    assert_eq!(walls_match_footprints(&model, &plans[1]), (207, 207));
    assert_eq!(spaces_match_footprints(&model, &plans[1]), (39, 39, 6));
    let l2 = &plans[1];
    assert_eq!(l2.items_of(PlanItemKind::Space).count(), 39);
    assert_eq!(l2.doors.len(), 36);
    // Doorways: on each level one opening no door fills reaches through the band, the lift's
    // (its doors are an IfcFlowTerminal): 1.232 m along the partition, as deep as the 0.124 m
    // partition although the opening's box reaches 3.05 m across it (IfcOpenShell: a 3.05 x
    // 1.23 m box). The other eight unfilled openings are narrower or start above the floor.
    for (plan, id) in [(l1, 1057), (l2, 1056)] {
        let ids: Vec<u64> = plan.openings.iter().map(|o| o.door.0).collect();
        assert_eq!(ids, [id], "{:?}", plan.storey_name);
        let o = &plan.openings[0];
        assert!((o.clear_width_m - 1.2319).abs() < 1e-3, "{o:?}");
        assert!((o.depth_m - 0.124).abs() < 0.005, "{o:?}");
        assert!(
            (o.center.x - 23.88).abs() < 0.01 && (o.center.y + 20.725).abs() < 0.01,
            "{o:?}"
        );
        assert!(o.along.y.abs() > 0.999, "along the wall (y): {o:?}");
        assert_eq!(o.clear_width_source, ClearWidthSource::OpeningGeometry);
        assert_eq!(
            plan.items
                .iter()
                .filter(|i| i.kind == PlanItemKind::DoorOpening && i.class == "IfcOpeningElement")
                .count(),
            1
        );
    }
}

#[test]
fn the_test_buildings_gaps_are_its_door_widths() {
    let spec = poinav_author::DemoBuilding::default();
    let bytes = poinav_author::demo_building(&spec, "2026-01-01T00:00:00").unwrap();
    let model = Model::from_bytes("demo.ifc", bytes).unwrap();
    let plans = floor_plans(&model, &PlanOptions::default());
    assert_eq!(plans.len(), 1);
    let plan = &plans[0];
    assert!(plan.problems.is_empty(), "{:?}", plan.problems);
    let layout = spec.layout();
    assert_eq!(plan.doors.len(), 6);
    assert_eq!(plan.items_of(PlanItemKind::Space).count(), 7);
    for room in &layout.rooms {
        let want = DVec2::from(room.door.center);
        let door = plan
            .doors
            .iter()
            .find(|d| d.center.distance(want) < 0.01)
            .unwrap_or_else(|| panic!("no door at {want}"));
        let gap = plan.free_width_at(door, 3.0);
        println!(
            "{}: gap {gap:.4} m, door {:.2} m",
            room.door.name, room.door.width_m
        );
        assert!(
            (gap - room.door.width_m).abs() < 0.001,
            "{}: {gap}",
            room.door.name
        );
        assert!((door.clear_width_m - room.door.width_m).abs() < 1e-9);
        assert!(blocked(plan, door).is_none());
        // The test sees walls: 3 cm more than the gap (1 cm past the slack each side) is
        // blocked.
        let mut wider = door.clone();
        wider.clear_width_m = room.door.width_m + 0.03;
        assert!(blocked(plan, &wider).is_some());
        // Across the wall, the opening is free; beside it, the wall is there.
        let beside = door.center + door.along * (room.door.width_m / 2.0 + 0.05);
        assert!(plan.obstacles().any(|r| r.contains(beside)));
    }
    let widths: Vec<f64> = layout.rooms.iter().map(|r| r.door.width_m).collect();
    assert_eq!(widths, [1.0, 0.8, 1.0, 1.0, 1.0, 1.0]);
}

#[test]
fn the_band_decides_what_is_in_the_way() {
    // A low band sees the walls of the test building; a band above the walls sees nothing.
    let spec = poinav_author::DemoBuilding::default();
    let bytes = poinav_author::demo_building(&spec, "2026-01-01T00:00:00").unwrap();
    let model = Model::from_bytes("demo.ifc", bytes).unwrap();
    let high = PlanOptions {
        band_min_m: 3.5,
        band_max_m: 4.0,
        ..PlanOptions::default()
    };
    let plans = floor_plans(&model, &high);
    assert_eq!(plans[0].obstacles().count(), 0);
    assert_eq!(plans[0].doors.len(), 0, "openings end at 2.1 m");
    // Above the doors (2.1 m) the walls are whole: no gap.
    let lintel = PlanOptions {
        band_min_m: 2.2,
        band_max_m: 2.5,
        ..PlanOptions::default()
    };
    let plans = floor_plans(&model, &lintel);
    let door = &floor_plans(&model, &PlanOptions::default())[0].doors[0];
    assert!(plans[0].obstacles().any(|r| r.contains(door.center)));
}

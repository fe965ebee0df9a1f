//! Occupancy grids of hand-made floors: every door that is FULL_ACCESS for the default profile
//! has a free path through it in the inflated grid and no BLOCKED one has; cells, furniture
//! and unknown space as the options say.

mod support;

use poinav_nav::graph::Topology;
use poinav_nav::grid::CellState;
use poinav_nav::{Building, Floor, FurnitureMode, GridOptions, InflationOptions, NavGrid};
use poinav_poi::{AccessibilityStatus, RobotProfile};
use support::{demo, demo_floor, office_floor, rotated};

/// Per door: (name, status, passable in the inflated grid).
fn door_checks(floor: &Floor, profile: &RobotProfile) -> Vec<(String, AccessibilityStatus, bool)> {
    door_checks_with(floor, profile, &GridOptions::default())
}

fn door_checks_with(
    floor: &Floor,
    profile: &RobotProfile,
    options: &GridOptions,
) -> Vec<(String, AccessibilityStatus, bool)> {
    let building = Building::single(floor.clone());
    let topo = Topology::build(&building);
    let grid = NavGrid::build(floor, profile, options, &InflationOptions::default()).unwrap();
    floor
        .doors
        .iter()
        .enumerate()
        .map(|(k, d)| {
            let outside = topo
                .door(0, poinav_nav::DoorIdx::new(k))
                .and_then(|s| s.outside_side());
            (
                d.name.clone().unwrap(),
                grid.occupancy.doors[k].status,
                grid.door_passable(k, outside),
            )
        })
        .collect()
}

fn assert_full_open_blocked_closed(floor: &Floor) -> (usize, usize, usize) {
    // Doors opened or closed by status, and all doors open (geometry and inflation alone):
    // both agree with the clear-width rule.
    let geometry_only = GridOptions {
        doors_by_status: false,
        ..Default::default()
    };
    let by_status = assert_doors(floor, &GridOptions::default());
    assert_eq!(assert_doors(floor, &geometry_only), by_status);
    by_status
}

fn assert_doors(floor: &Floor, options: &GridOptions) -> (usize, usize, usize) {
    let checks = door_checks_with(floor, &RobotProfile::paper(), options);
    let (mut full, mut restricted, mut blocked) = (0, 0, 0);
    for (name, status, free) in &checks {
        match status {
            AccessibilityStatus::FullAccess => {
                full += 1;
                assert!(free, "{name} is FULL_ACCESS but has no free path");
            }
            AccessibilityStatus::Blocked => {
                blocked += 1;
                assert!(!free, "{name} is BLOCKED but has a free path");
            }
            AccessibilityStatus::Restricted => {
                restricted += 1;
                // 0.80 m for a 0.70 m robot: 0.05 m each side, room for its centre.
                assert!(
                    free,
                    "{name} is RESTRICTED (wider than the robot) but closed"
                );
            }
            AccessibilityStatus::PendingValidation => {}
        }
    }
    (full, restricted, blocked)
}

#[test]
fn demo_building_doors_per_status() {
    let (full, restricted, blocked) = assert_full_open_blocked_closed(&demo());
    assert_eq!((full, restricted, blocked), (5, 1, 0));
    // Room 2's door narrowed to 0.60 m: BLOCKED and closed in the grid.
    let narrow = demo_floor(&poinav_author::DemoBuilding {
        room2_door_width_m: 0.6,
        ..Default::default()
    });
    let checks = door_checks(&narrow, &RobotProfile::paper());
    let room2 = checks.iter().find(|c| c.0 == "Door Room 2").unwrap();
    assert_eq!(room2.1, AccessibilityStatus::Blocked);
    assert!(!room2.2);
    assert_eq!(assert_full_open_blocked_closed(&narrow), (5, 0, 1));
}

#[test]
fn rotated_demo_building_keeps_its_doors() {
    for angle in [0.3_f64, 0.785, 1.2] {
        let (full, restricted, blocked) = assert_full_open_blocked_closed(&rotated(&demo(), angle));
        assert_eq!((full, restricted, blocked), (5, 1, 0), "angle {angle}");
    }
}

#[test]
fn office_doors_per_status() {
    let floor = office_floor();
    assert_eq!(floor.zones.len(), 101);
    let (full, restricted, blocked) = assert_full_open_blocked_closed(&floor);
    assert_eq!(full + restricted + blocked, 100);
    assert_eq!(blocked, 1);
    assert_eq!(restricted, 14);
}

#[test]
fn narrowing_only_the_clear_width_closes_the_passage() {
    // The ring stays 1.0 m wide; a 0.60 m clear width (thick linings) is BLOCKED and the
    // linings are solid in the grid.
    let mut floor = demo();
    let d = floor
        .doors
        .iter_mut()
        .find(|d| d.name.as_deref() == Some("Door Room 4"))
        .unwrap();
    d.clear_width_m = 0.6;
    let checks = door_checks(&floor, &RobotProfile::paper());
    let c = checks.iter().find(|c| c.0 == "Door Room 4").unwrap();
    assert_eq!((c.1, c.2), (AccessibilityStatus::Blocked, false));
    // A narrow robot for which 0.60 m is enough gets through the same grid geometry.
    let mut small = RobotProfile::paper();
    small.width_m = 0.4;
    small.length_m = 0.4;
    small.min_clearance_width_m = Some(0.55);
    let checks = door_checks(&floor, &small);
    let c = checks.iter().find(|c| c.0 == "Door Room 4").unwrap();
    assert_eq!((c.1, c.2), (AccessibilityStatus::FullAccess, true));
}

#[test]
fn cells_free_occupied_unknown() {
    let floor = demo();
    let profile = RobotProfile::paper();
    let g = poinav_nav::OccupancyGrid::build(&floor, &profile, &GridOptions::default()).unwrap();
    // 12.4 x 10.8 m inside, 0.2 m walls, 0.5 m padding: 13.8 x 12.2 m in 0.05 m cells.
    assert_eq!(g.resolution_m, 0.05);
    assert_eq!((g.width, g.height), (276, 244));
    assert!((g.origin.x - -0.7).abs() < 1e-9 && (g.origin.y - -0.7).abs() < 1e-9);
    let at = |x: f64, y: f64| g.cells[g.cell_of(glam::DVec2::new(x, y)).unwrap()];
    assert_eq!(at(2.0, 2.0), CellState::Free); // Room 1
    assert_eq!(at(2.0, 4.1), CellState::Free); // Door Room 1
    assert_eq!(at(1.0, 4.1), CellState::Occupied); // corridor wall
    assert_eq!(at(-0.1, 5.0), CellState::Occupied); // exterior wall
    assert_eq!(at(-0.5, 5.0), CellState::Unknown); // outside
    let [free, occupied, unknown] = g.counts();
    // Zones: 6 rooms of 4 x 4 m and a 12.4 x 2.4 m corridor, plus the door passages
    // (5 x 1.0 m + 0.8 m, 0.2 m deep), in 0.05 m cells.
    let zones = 6.0 * 16.0 + 12.4 * 2.4;
    let passages = (5.0 + 0.8) * 0.2;
    assert_eq!(free, ((zones + passages) / 0.0025_f64).round() as usize);
    assert_eq!(free + occupied + unknown, 276 * 244);
}

#[test]
fn furniture_as_obstacle_or_unknown() {
    let floor = office_floor();
    let profile = RobotProfile::paper();
    let obstacle =
        poinav_nav::OccupancyGrid::build(&floor, &profile, &GridOptions::default()).unwrap();
    let unknown = poinav_nav::OccupancyGrid::build(
        &floor,
        &profile,
        &GridOptions {
            furniture: FurnitureMode::Unknown,
            ..Default::default()
        },
    )
    .unwrap();
    let desk_cells = (1.4 * 0.7 / 0.0025_f64).round() as usize * 98;
    assert_eq!(obstacle.counts()[1] - unknown.counts()[1], desk_cells);
    assert_eq!(unknown.counts()[2] - obstacle.counts()[2], desk_cells);
}

#[test]
fn narrow_door_in_a_thick_wall_and_an_empty_storey() {
    use support::{door, rect, room, wall};
    // Two rooms with a 1.0 m thick wall between them and a 0.85 m door: the door's ring is
    // deeper than wide, its width axis still runs along the wall.
    let floor = Floor {
        name: "Thick".into(),
        elevation_m: 0.0,
        obstacles: vec![
            wall(
                "outer",
                vec![
                    rect(-0.2, -0.2, 9.2, 0.0),
                    rect(-0.2, 4.0, 9.2, 4.2),
                    rect(-0.2, 0.0, 0.0, 4.0),
                    rect(9.0, 0.0, 9.2, 4.0),
                ],
            ),
            wall(
                "thick",
                vec![rect(4.0, 0.0, 5.0, 1.575), rect(4.0, 2.425, 5.0, 4.0)],
            ),
        ],
        doors: vec![door("d", "Thick door", rect(4.0, 1.575, 5.0, 2.425), 0.85)],
        zones: vec![
            room("a", "West", rect(0.0, 0.0, 4.0, 4.0)),
            room("b", "East", rect(5.0, 0.0, 9.0, 4.0)),
        ],
    };
    let building = Building {
        floors: vec![
            Floor {
                name: "Empty".into(),
                ..Floor::default()
            },
            floor.clone(),
        ],
        connections: vec![],
        levels: vec![],
    };
    let topo = Topology::build(&building);
    let mut sides = topo.door(1, poinav_nav::DoorIdx::new(0)).unwrap().zones;
    sides.sort();
    assert_eq!(
        sides,
        [Some(0), Some(1)].map(|z| z.map(poinav_nav::ZoneIdx::new))
    );
    let checks = door_checks(&floor, &RobotProfile::paper());
    assert_eq!(checks[0].1, AccessibilityStatus::Restricted);
    assert!(checks[0].2);
    let nav =
        poinav_nav::Navigator::new(&building, &RobotProfile::paper(), &Default::default()).unwrap();
    let empty = &nav.floors[0].grid.occupancy;
    assert_eq!(empty.counts()[2], empty.len());
    let route = nav
        .route(
            &poinav_nav::Place::zone("West"),
            &poinav_nav::Place::zone("East"),
        )
        .unwrap();
    assert_eq!(route.doors.len(), 1);
    assert_eq!(route.legs[0].floor_name, "Thick");
}

#[test]
fn narrowest_passable_door() {
    // Through an open door the clearance is exact (half the passage less the distance from its
    // axis), so the robot's centre passes once some row of cell centres runs within
    // (clear width - robot width) / 2 of the door's axis: at 0.05 m cells, 0.70 m plus at most
    // twice the half-diagonal of a cell. Measured every 15 degrees: 0.73 to 0.75 m (0.73 to
    // 0.78 m before the exact passage clearance, when the jambs' rasterisation also counted).
    let mut narrowest = Vec::new();
    for step in 0..=6 {
        let angle = f64::from(step) * 15f64.to_radians();
        let mut first = None;
        for cm in 70..=80 {
            let floor = rotated(
                &demo_floor(&poinav_author::DemoBuilding {
                    room2_door_width_m: f64::from(cm) / 100.0,
                    ..Default::default()
                }),
                angle,
            );
            let checks = door_checks(&floor, &RobotProfile::paper());
            let room2 = checks.iter().find(|c| c.0 == "Door Room 2").unwrap();
            if room2.2 && first.is_none() {
                first = Some(cm);
            }
            if first.is_some() {
                assert!(
                    room2.2,
                    "{cm} cm at {angle} rad closed after a narrower one opened"
                );
            }
        }
        narrowest.push(first.unwrap());
    }
    println!("narrowest passable door (cm) every 15 degrees: {narrowest:?}");
    assert!(narrowest.iter().all(|cm| *cm <= 75), "{narrowest:?}");
    assert!(narrowest.iter().all(|cm| *cm > 70), "{narrowest:?}");
}

#[test]
fn an_open_entrance_has_a_free_apron_outside_and_routes_start_there() {
    use poinav_nav::{NavOptions, Navigator, Place};
    use support::{door, rect, room, wall};
    // A 4 x 4 m room inside 0.2 m walls, a 1.0 m entrance in the south wall (y -0.2..0).
    let floor = Floor {
        name: "Ground".into(),
        obstacles: vec![wall(
            "outer",
            vec![
                rect(-0.2, -0.2, 1.5, 0.0),
                rect(2.5, -0.2, 4.2, 0.0),
                rect(-0.2, 4.0, 4.2, 4.2),
                rect(-0.2, 0.0, 0.0, 4.0),
                rect(4.0, 0.0, 4.2, 4.0),
            ],
        )],
        doors: vec![door("entrance", "Entrance", rect(1.5, -0.2, 2.5, 0.0), 1.0)],
        zones: vec![room("room", "Room", rect(0.0, 0.0, 4.0, 4.0))],
        ..Floor::default()
    };
    let profile = RobotProfile::paper();
    let grid = |apron: f64| {
        poinav_nav::OccupancyGrid::build(
            &floor,
            &profile,
            &GridOptions {
                entrance_apron_m: apron,
                ..Default::default()
            },
        )
        .unwrap()
    };
    let (with, without) = (grid(1.0), grid(0.0));
    // 1.0 x 1.0 m of unknown outside cells become free: 400 cells of 0.05 m (the grid grows
    // to hold the apron).
    assert_eq!(with.counts()[0] - without.counts()[0], 400);
    assert!(with.origin.y <= -1.2 - 0.5 && without.origin.y > -1.2);
    let p = glam::DVec2::new(2.0, -0.6);
    assert_eq!(with.cells[with.cell_of(p).unwrap()], CellState::Free);
    assert_eq!(
        without.cells[without.cell_of(p).unwrap()],
        CellState::Unknown
    );
    // Beside the apron the outside stays unknown.
    let beside = with.cell_of(glam::DVec2::new(0.5, -0.7)).unwrap();
    assert_eq!(with.cells[beside], CellState::Unknown);

    let building = Building::single(floor.clone());
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    let route = nav
        .route(&"outside".parse::<Place>().unwrap(), &Place::zone("Room"))
        .unwrap();
    assert_eq!(route.doors[0].name.as_deref(), Some("Entrance"));
    let start = route.legs[0].polyline[0];
    assert!(start[1] < -0.2 && start[1] >= -1.2, "{start:?}");
    // A closed entrance has no apron, and no route comes in from outside.
    let mut closed = floor.clone();
    closed.doors[0].clear_width_m = 0.6;
    closed.doors[0].classified_width_m = Some(0.6);
    let building = Building::single(closed);
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    let err = nav
        .route(&"outside".parse::<Place>().unwrap(), &Place::zone("Room"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("no entrance is open for paper-robot: Entrance (BLOCKED"),
        "{err}"
    );
}

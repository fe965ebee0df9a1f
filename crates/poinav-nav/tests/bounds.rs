//! Size bounds of rasterising and the graph ([`poinav_nav::bounds`]) on hand-made floors: an
//! obstacle, a zone or a door past a bound is unknown over its bounding box (never free), a door
//! whose sides are not decided is neither an entrance nor passable, each is named with its
//! bound, and floors within the bounds give no diagnostics.

mod support;

use glam::DVec2;
use poinav_nav::bounds::{Stage, StageBounds, ELEMENT_VERTICES};
use poinav_nav::{
    AuditOptions, Building, Floor, FloorObstacle, GridOptions, NavOptions, Navigator, ObstacleKind,
    OccupancyGrid, Place,
};
use poinav_poi::RobotProfile;
use support::{door, office_floor, rect, room, wall};

/// A ring of `n` vertices around the circle at `c` of radius `r`, with the four extreme
/// points among them (n a multiple of 4), so its bounding box is exactly `c -+ r`.
fn circle(c: DVec2, r: f64, n: usize) -> Vec<DVec2> {
    (0..n)
        .map(|k| {
            let quarter = n / 4;
            let (q, m) = (k / quarter, k % quarter);
            let a = std::f64::consts::FRAC_PI_2 * (q as f64 + m as f64 / quarter as f64);
            let (s, co) = match (q, m) {
                (_, 0) => [(0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0)][q],
                _ => a.sin_cos(),
            };
            c + DVec2::new(co, s) * r
        })
        .collect()
}

/// The axis-aligned rectangle `x0..x1 x y0..y1` as a ring of `n` vertices (each edge split
/// evenly; n a multiple of 4).
fn dense_rect(x0: f64, y0: f64, x1: f64, y1: f64, n: usize) -> Vec<DVec2> {
    let q = n / 4;
    let corners = [
        DVec2::new(x0, y0),
        DVec2::new(x1, y0),
        DVec2::new(x1, y1),
        DVec2::new(x0, y1),
    ];
    (0..4)
        .flat_map(|e| {
            let (a, b) = (corners[e], corners[(e + 1) % 4]);
            (0..q).map(move |k| a.lerp(b, k as f64 / q as f64))
        })
        .collect()
}

/// Two rooms, West (0..5) and East (5.2..10) by 0..5 m, inside 0.2 m walls, a door between
/// them and an entrance door in East's outer wall at x = 10..10.2.
fn two_rooms(east_vertices: usize) -> Floor {
    let t = 0.2;
    let east = if east_vertices <= 4 {
        rect(5.2, 0.0, 10.0, 5.0)
    } else {
        dense_rect(5.2, 0.0, 10.0, 5.0, east_vertices).into()
    };
    Floor {
        name: "Level 1".into(),
        elevation_m: 0.0,
        obstacles: vec![
            wall(
                "outer",
                vec![
                    rect(-t, -t, 10.0 + t, 0.0),
                    rect(-t, 5.0, 10.0 + t, 5.0 + t),
                    rect(-t, 0.0, 0.0, 5.0),
                    rect(10.0, 0.0, 10.0 + t, 2.0),
                    rect(10.0, 3.0, 10.0 + t, 5.0),
                ],
            ),
            wall(
                "middle",
                vec![rect(5.0, 0.0, 5.2, 2.0), rect(5.0, 3.0, 5.2, 5.0)],
            ),
        ],
        doors: vec![
            door("inner-door", "Inner", rect(5.0, 2.0, 5.2, 3.0), 1.0),
            door("front-door", "Front", rect(10.0, 2.0, 10.0 + t, 3.0), 1.0),
        ],
        zones: vec![
            room("west", "West", rect(0.0, 0.0, 5.0, 5.0)),
            room("east", "East", east),
        ],
    }
}

fn grid(floor: &Floor, options: &GridOptions) -> OccupancyGrid {
    OccupancyGrid::build(floor, &RobotProfile::paper(), options).unwrap()
}

/// Cells whose centre lies in `lo..hi` (the fill's rule), and how many of each state.
fn in_box(g: &OccupancyGrid, lo: DVec2, hi: DVec2) -> (usize, [usize; 3]) {
    let mut counts = [0; 3];
    let mut n = 0;
    for i in 0..g.len() {
        let p = g.center(i);
        if p.x >= lo.x && p.x < hi.x && p.y >= lo.y && p.y <= hi.y {
            n += 1;
            counts[g.cells[i] as usize] += 1;
        }
    }
    (n, counts)
}

#[test]
fn an_obstacle_past_the_vertex_bound_is_unknown_over_its_box_and_named() {
    let mut floor = two_rooms(4);
    let n = 150_000;
    assert!(n > ELEMENT_VERTICES);
    // A round table in West, and one across East's outer wall (its box overlaps the wall).
    for (id, c, r) in [
        ("table", DVec2::new(2.5, 2.5), 1.0),
        ("planter", DVec2::new(9.9, 1.0), 0.5),
    ] {
        floor.obstacles.push(FloorObstacle {
            id: id.into(),
            class: "IfcFurniture".into(),
            kind: ObstacleKind::Furniture,
            rings: vec![circle(c, r, n).into()],
            roles: vec![],
        });
    }
    let g = grid(&floor, &GridOptions::default());
    // Table: 2 x 2 m at 5 cm, wholly in the room: 40 x 40 cells, every one unknown.
    let (cells, [free, occupied, unknown]) = in_box(&g, DVec2::new(1.5, 1.5), DVec2::new(3.5, 3.5));
    assert_eq!(cells, 1600);
    assert_eq!((free, occupied, unknown), (0, 0, 1600));
    // Planter: 1 x 1 m box (400 cells), 4 columns of wall (x 10..10.2) x 20 rows stay
    // occupied, the rest is unknown: 320; none free.
    let (cells, [free, occupied, unknown]) =
        in_box(&g, DVec2::new(9.4, 0.5), DVec2::new(10.4, 1.5));
    assert_eq!(cells, 400);
    assert_eq!((free, occupied, unknown), (0, 80, 320));
    // Without them those cells are free.
    let plain = grid(&two_rooms(4), &GridOptions::default());
    let (_, [free, _, _]) = in_box(&plain, DVec2::new(1.5, 1.5), DVec2::new(3.5, 3.5));
    assert_eq!(free, 1600);
    assert!(plain.gave_up.is_empty());

    let named: Vec<(&str, &str, Stage, &str)> = g
        .gave_up
        .iter()
        .map(|d| {
            (
                d.element.as_str(),
                d.class.as_str(),
                d.stage,
                d.bound.as_str(),
            )
        })
        .collect();
    assert_eq!(
        named,
        [
            (
                "table",
                "IfcFurniture",
                Stage::Raster,
                "vertices: 150000 > 100000"
            ),
            (
                "planter",
                "IfcFurniture",
                Stage::Raster,
                "vertices: 150000 > 100000"
            ),
        ]
    );
    assert_eq!(
        g.gave_up[0].message(),
        "storey Level 1: IfcFurniture table: raster bound passed (vertices: 150000 > 100000): \
         its bounding box is unknown"
    );
}

#[test]
fn an_obstacle_past_the_work_bound_is_unknown_and_the_bound_named() {
    // Lowered bound: a column of two rectangles, one spanning 20 rows and one 10, is
    // 4 x 20 + 4 x 10 = 120 edge-row tests.
    let mut floor = two_rooms(4);
    floor.obstacles.push(wall(
        "column",
        vec![rect(1.0, 1.0, 1.5, 2.0), rect(3.0, 1.0, 3.5, 1.5)],
    ));
    let options = GridOptions {
        bounds: StageBounds {
            raster_work: 119,
            ..StageBounds::default()
        },
        ..GridOptions::default()
    };
    let g = grid(&floor, &options);
    let column: Vec<_> = g.gave_up.iter().filter(|d| d.element == "column").collect();
    assert_eq!(column.len(), 1);
    assert_eq!(column[0].bound, "raster work: 120 > 119");
    // Its bounding box, 1..3.5 x 1..2 m: 50 x 20 cells, all unknown.
    let (cells, counts) = in_box(&g, DVec2::new(1.0, 1.0), DVec2::new(3.5, 2.0));
    assert_eq!((cells, counts), (1000, [0, 0, 1000]));
}

#[test]
fn a_zone_past_the_bound_is_unknown_and_its_doors_undecided_closed_and_no_entrance() {
    let plain = Building::single(two_rooms(4));
    let profile = RobotProfile::paper();
    let nav = Navigator::new(&plain, &profile, &NavOptions::default()).unwrap();
    assert!(nav.gave_up.is_empty());
    // Within the bounds the front door is an entrance and both doors are open.
    assert_eq!(nav.topology.entrances().len(), 1);
    assert!(nav.open.iter().all(|o| *o));
    let east_free = nav.floors[0].grid.occupancy.counts()[0];

    let building = Building::single(two_rooms(120_000));
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    let g = &nav.floors[0].grid.occupancy;
    // East (5.2..10 x 0..5: 96 x 100 cells) is enclosed by walls but unknown, not free.
    let (cells, [free, _, unknown]) = in_box(g, DVec2::new(5.2, 0.0), DVec2::new(10.0, 5.0));
    assert_eq!((cells, free, unknown), (9600, 0, 9600));
    assert!(g.counts()[0] < east_free - 9000);
    let named: Vec<(&str, &str, Stage, &str)> = nav
        .gave_up
        .iter()
        .map(|d| {
            (
                d.element.as_str(),
                d.class.as_str(),
                d.stage,
                d.bound.as_str(),
            )
        })
        .collect();
    assert_eq!(
        named,
        [
            (
                "east",
                "IfcSpace",
                Stage::Raster,
                "vertices: 120000 > 100000"
            ),
            (
                "inner-door",
                "IfcDoor",
                Stage::Graph,
                "zone vertices near: 120004 > 100000"
            ),
            (
                "front-door",
                "IfcDoor",
                Stage::Graph,
                "zone vertices near: 120000 > 100000"
            ),
        ]
    );
    // Neither door is an entrance, open or passable; no apron outside the front door.
    assert!(nav.topology.entrances().is_empty());
    for d in &nav.topology.doors {
        assert!(d.gave_up && !d.exterior(), "{d:?}");
        assert!(!nav.grid_passable[d.node] && !nav.open[d.node]);
        assert!(nav.closed_reason(d.node).contains("given up on"));
    }
    let (_, [free, _, _]) = in_box(g, DVec2::new(10.2, 2.0), DVec2::new(11.2, 3.0));
    assert_eq!(free, 0);
    // West cannot reach East.
    assert!(nav
        .route(&Place::zone("West"), &Place::zone("East"))
        .is_err());
    // The audit lists them, in its JSON and its warnings.
    let report = poinav_nav::audit(
        &building,
        std::slice::from_ref(&profile),
        &AuditOptions::default(),
    )
    .unwrap();
    let json = report.to_json();
    let listed: Vec<&str> = json["gave_up"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["element"].as_str().unwrap())
        .collect();
    assert_eq!(listed, ["east", "front-door", "inner-door"]);
    assert_eq!(json["gave_up"][0]["stage"], "raster");
    assert!(report
        .warnings
        .iter()
        .any(|w| w.contains("IfcDoor front-door: graph bound passed")));
}

#[test]
fn a_door_whose_passage_search_passes_the_cell_bound_is_closed_and_named() {
    let floor = two_rooms(4);
    let options = NavOptions {
        grid: GridOptions {
            bounds: StageBounds {
                door_cells: 100,
                ..StageBounds::default()
            },
            ..GridOptions::default()
        },
        ..NavOptions::default()
    };
    let building = Building::single(floor);
    let nav = Navigator::new(&building, &RobotProfile::paper(), &options).unwrap();
    assert_eq!(nav.gave_up.len(), 2);
    assert!(nav.gave_up.iter().all(|d| d.stage == Stage::Graph
        && d.bound.starts_with("passage cells: ")
        && d.bound.ends_with(" > 100")));
    assert!(nav.topology.entrances().is_empty());
    assert!(nav.topology.doors.iter().all(|d| !nav.open[d.node]));
}

#[test]
fn floors_within_the_bounds_give_no_diagnostics() {
    let building = Building::single(office_floor());
    let nav = Navigator::new(&building, &RobotProfile::paper(), &NavOptions::default()).unwrap();
    assert!(nav.gave_up.is_empty(), "{:?}", nav.gave_up);
    assert!(nav.topology.doors.iter().all(|d| !d.gave_up));
}

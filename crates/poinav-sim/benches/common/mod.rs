//! Buildings and robot placements shared by the simulator benchmarks: the paper's test building
//! and office-a.ifc's "Level 1" as floors, and free start spots inside their zones.

// Each bench binary uses its own subset of these helpers.
#![allow(dead_code)]

use glam::DVec2;
use poinav_nav::polygon::{boundary_distance, contains, segment_distance};
use poinav_nav::Floor;
use poinav_poi::{RobotProfile, RuleSet};

/// The storey of office-a.ifc the benchmarks use.
pub const OFFICE_STOREY: &str = "Level 1";

/// The paper's test building, as `poinav simulate` prepares it.
pub fn demo_floor() -> Floor {
    let scenario = poinav_sim::Scenario::from_toml(
        "name = \"bench\"\nduration_s = 1.0\n[building]\ndemo = {}\n[[robot]]\nname = \"R\"\nstart = { x = 1.0, y = 5.4 }\ncontroller = { kind = \"idle\" }\n",
        "bench.toml",
        std::path::Path::new("."),
    )
    .unwrap();
    poinav_bridge::prepare(&scenario, None)
        .unwrap()
        .floor()
        .clone()
}

/// office-a.ifc's [`OFFICE_STOREY`], classified with the default rules and the paper's robot
/// and built by [`poinav_bridge::building`], as `poinav simulate` prepares it.
pub fn office_floor() -> Floor {
    let path = poinav_testkit::corpus_file("office-a.ifc");
    let bytes = std::fs::read(&path).unwrap_or_else(|e| {
        panic!(
            "cannot read {} ({e}); set POINAV_SHARED to the folder holding ifc/",
            path.display()
        )
    });
    let model = poinav_ifc::Model::from_bytes("office-a.ifc", bytes).unwrap();
    let classification = poinav_poi::classify(&model, &RuleSet::defaults(), &RobotProfile::paper());
    let made = poinav_bridge::building(&model, &classification, &poinav_bridge::Stages::of(&model));
    let i = poinav_bridge::pick(&made.storeys, Some(OFFICE_STOREY)).unwrap();
    made.building.floors[i].clone()
}

/// Every obstacle edge of `floor` as `(a, b)`, degenerate edges left out (as the world index
/// does).
pub fn obstacle_edges(floor: &Floor) -> Vec<(DVec2, DVec2)> {
    let mut out = Vec::new();
    for o in &floor.obstacles {
        for ring in &o.rings {
            let n = ring.len();
            if n < 2 {
                continue;
            }
            for i in 0..n {
                let (a, b) = (ring[i], ring[(i + 1) % n]);
                if a.distance_squared(b) > 1e-18 {
                    out.push((a, b));
                }
            }
        }
    }
    out
}

/// Points on a `spacing` grid inside the zones of `floor`, each at least `clear` from every
/// obstacle edge, outside every obstacle and at least `clear` inside its zone's outline;
/// zone by zone, row by row.
pub fn free_spots(floor: &Floor, spacing: f64, clear: f64) -> Vec<DVec2> {
    let edges = obstacle_edges(floor);
    let mut spots = Vec::new();
    for z in &floor.zones {
        let Some((lo, hi)) = poinav_nav::polygon::bounds(&z.ring) else {
            continue;
        };
        let mut y = lo.y + clear;
        while y <= hi.y - clear {
            let mut x = lo.x + clear;
            while x <= hi.x - clear {
                let p = DVec2::new(x, y);
                let inside = contains(&z.ring, p) && boundary_distance(&z.ring, p) >= clear;
                let free = inside
                    && edges
                        .iter()
                        .all(|&(a, b)| segment_distance(a, b, p) >= clear)
                    && !floor
                        .obstacles
                        .iter()
                        .flat_map(|o| &o.rings)
                        .any(|r| contains(r, p));
                if free {
                    spots.push(p);
                }
                x += spacing;
            }
            y += spacing;
        }
    }
    spots
}

/// `n` of `spots`, spread evenly over the list.
pub fn spread(spots: &[DVec2], n: usize) -> Vec<DVec2> {
    assert!(spots.len() >= n, "{} places for {n} robots", spots.len());
    let step = spots.len() / n;
    (0..n).map(|i| spots[i * step]).collect()
}

/// A big open floor for `n` robots: a square hall (one C-1 zone, MinInterRobotSeparation 2 m,
/// SPEED_REDUCTION) about 3 m of floor per robot each way, outer walls and a 0.4 m column every
/// 12 m, and `n` robots on a 3 m grid driven by keys: forward, then a short turn
/// to the left or right that differs from robot to robot, so they spread, meet and touch.
pub fn open_floor(n: usize) -> (Floor, Vec<poinav_sim::RobotSetup>) {
    use poinav_nav::{FloorObstacle, FloorZone, ObstacleKind};
    use poinav_poi::{CoordinationProtocol, Role};
    use poinav_sim::controller::{ControllerSpec, KeyPress, KeyScheme};
    let side = (n as f64).sqrt().ceil() as usize;
    let size = side as f64 * 3.0 + 4.0;
    use poinav_nav::polygon::rect;
    let obstacle = |id: String, ring: poinav_nav::Ring| FloorObstacle {
        id: id.into(),
        class: "IfcWall".into(),
        kind: ObstacleKind::Structure,
        rings: vec![ring],
        roles: vec![Role::Avoidance, Role::PathGuidance],
    };
    let mut obstacles = vec![
        obstacle("south".into(), rect(-0.2, -0.2, size + 0.2, 0.0)),
        obstacle("north".into(), rect(-0.2, size, size + 0.2, size + 0.2)),
        obstacle("west".into(), rect(-0.2, 0.0, 0.0, size)),
        obstacle("east".into(), rect(size, 0.0, size + 0.2, size)),
    ];
    let mut c = 12.0;
    while c < size - 2.0 {
        let mut d = 12.0;
        while d < size - 2.0 {
            obstacles.push(obstacle(
                format!("column {c} {d}"),
                rect(c - 1.7, d - 1.7, c - 1.3, d - 1.3),
            ));
            d += 12.0;
        }
        c += 12.0;
    }
    let floor = Floor {
        name: format!("hall for {n}"),
        obstacles,
        zones: vec![FloorZone {
            id: "hall".into(),
            name: Some("Hall".into()),
            long_name: None,
            ring: rect(0.0, 0.0, size, size),
            roles: vec![Role::MultiRobotZone],
            coordination: Some((2.0, CoordinationProtocol::SpeedReduction)),
        }],
        ..Floor::default()
    };
    let robots = (0..n)
        .map(|i| {
            let (gx, gy) = (i % side, i / side);
            let turn = if i % 2 == 0 { "Left" } else { "Right" };
            let t0 = 0.1 + (i % 7) as f64 * 0.05;
            let script = [
                (0.0, "Up", true),
                (t0, turn, true),
                (t0 + 0.15, turn, false),
            ]
            .into_iter()
            .map(|(t, key, down)| KeyPress {
                t,
                key: key.into(),
                down,
            })
            .collect();
            poinav_sim::RobotSetup {
                name: format!("Robot{}", i + 1),
                global_id: None,
                profile: RobotProfile::paper(),
                start: DVec2::new(3.5 + gx as f64 * 3.0, 3.5 + gy as f64 * 3.0),
                heading_deg: ((i * 37) % 360) as f64,
                controller: ControllerSpec::Keys {
                    scheme: KeyScheme::Arrows,
                    script,
                },
                priority: 0,
                brush_on: false,
                drive_force_n: 50.0,
                brake_force_n: 100.0,
            }
        })
        .collect();
    (floor, robots)
}

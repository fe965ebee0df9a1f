//! Property tests of the occupancy grid's world/cell conversion, for rooms anywhere (far from
//! the origin, negative coordinates) at any resolution: every cell's centre maps back to that
//! cell, every point maps to the cell whose centre is within half a cell of it, points outside
//! map to none, the grid covers the floor, and a room's interior is free and its walls occupied.

use glam::DVec2;
use poinav_nav::grid::{CellState, GridOptions, OccupancyGrid};
use poinav_nav::{Floor, FloorObstacle, FloorZone, ObstacleKind};
use poinav_poi::{RobotProfile, Role};
use proptest::prelude::*;

fn rect(lo: DVec2, hi: DVec2) -> poinav_nav::Ring {
    poinav_nav::polygon::rect(lo.x, lo.y, hi.x, hi.y)
}

/// A `w` x `h` room at `at` inside 0.2 m walls.
fn room(at: DVec2, w: f64, h: f64) -> Floor {
    let t = 0.2;
    let wall = |id: &str, lo: DVec2, hi: DVec2| FloorObstacle {
        id: id.into(),
        class: "IfcWall".into(),
        kind: ObstacleKind::Structure,
        rings: vec![rect(at + lo, at + hi)],
        roles: vec![Role::Avoidance],
    };
    Floor {
        name: "F".into(),
        obstacles: vec![
            wall("s", DVec2::new(-t, -t), DVec2::new(w + t, 0.0)),
            wall("n", DVec2::new(-t, h), DVec2::new(w + t, h + t)),
            wall("w", DVec2::new(-t, 0.0), DVec2::new(0.0, h)),
            wall("e", DVec2::new(w, 0.0), DVec2::new(w + t, h)),
        ],
        zones: vec![FloorZone {
            id: "z".into(),
            name: Some("Room".into()),
            long_name: None,
            ring: rect(at, at + DVec2::new(w, h)),
            roles: vec![Role::Destination],
            coordination: None,
        }],
        ..Floor::default()
    }
}

fn setup() -> impl Strategy<Value = (DVec2, f64, f64, f64)> {
    (
        -50_000.0f64..50_000.0,
        -50_000.0f64..50_000.0,
        1.0f64..12.0,
        1.0f64..12.0,
        prop::sample::select(vec![0.02, 0.025, 0.05, 0.1, 0.2, 0.25]),
    )
        .prop_map(|(x, y, w, h, r)| (DVec2::new(x, y), w, h, r))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn cells_and_world_points_convert_both_ways((at, w, h, res) in setup(), fx in 0.0f64..1.0, fy in 0.0f64..1.0) {
        let floor = room(at, w, h);
        let options = GridOptions { resolution_m: res, ..GridOptions::default() };
        let g = OccupancyGrid::build(&floor, &RobotProfile::paper(), &options).unwrap();
        // The grid covers the floor with its walls.
        let far = g.origin + DVec2::new(g.width as f64, g.height as f64) * res;
        prop_assert!(g.origin.x <= at.x - 0.2 && g.origin.y <= at.y - 0.2);
        prop_assert!(far.x >= at.x + w + 0.2 && far.y >= at.y + h + 0.2);
        // Cell centres map back to their cell (corners, edges and a spread of cells).
        let n = g.len();
        for i in [0, g.width - 1, n - g.width, n - 1, n / 2, n / 3, (n * 7) / 11] {
            prop_assert_eq!(g.cell_of(g.center(i)), Some(i));
        }
        // Any point in the grid is in the cell whose centre is within half a cell.
        let p = g.origin + DVec2::new(fx * g.width as f64, fy * g.height as f64) * res;
        if let Some(i) = g.cell_of(p) {
            let d = (g.center(i) - p).abs();
            let tol = res * 0.5 + 1e-6 * (1.0 + p.abs().max_element() * 1e-6);
            prop_assert!(d.x <= tol && d.y <= tol, "{p} -> {i} at {}", g.center(i));
        } else {
            // Only the far edges may round outside.
            prop_assert!(fx > 0.999_999 || fy > 0.999_999);
        }
        // Outside: none.
        prop_assert_eq!(g.cell_of(g.origin - DVec2::splat(res * 0.5)), None);
        prop_assert_eq!(g.cell_of(far + DVec2::splat(res * 0.5)), None);
        // The room's centre is free; the middle of the south wall occupied where the 0.2 m wall
        // is at least two cells thick (cells are filled by their centres).
        let centre = g.cell_of(at + DVec2::new(w, h) * 0.5).unwrap();
        prop_assert_eq!(g.cells[centre], CellState::Free);
        if res <= 0.1 {
            let wall = g.cell_of(at + DVec2::new(w * 0.5, -0.1)).unwrap();
            prop_assert_eq!(g.cells[wall], CellState::Occupied);
        }
    }
}

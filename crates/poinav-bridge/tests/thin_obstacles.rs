//! Thin and open geometry is an obstacle, never free space (issue 15, point 2): a fence modelled
//! as an extruded open profile (a surface), a wall modelled as a surface model and a closed
//! 5 mm glass panel, each across a room of a model IfcOpenShell writes
//! (`tests/ifcos/author_thin.py`), are lines of occupied cells in the navigation grid that no
//! route crosses; each of IfcOpenShell's mesh vertices of them, projected, lies on the floor's
//! obstacle, which is the plan's section as it is (the glass's exact strip, the surfaces'
//! 1 cm lines: what the simulator's rays hit). Without them (the fence and the surface wall had
//! no section, and no cell centre falls in the glass's 5 mm) the same routes exist. A panel
//! below the plan's band and one above it stay free. A 5 mm glazed sidelight (an IfcWindow)
//! right beside a door is drawn whole, also next to the door's passage.

use std::path::Path;

use glam::DVec2;
use poinav_bridge::{building, Stages};
use poinav_geom::section_lines::LINE_WIDTH_M;
use poinav_geom::{polygon, FloorPlan, PlanItemKind, PlanSource};
use poinav_ifc::Model;
use poinav_nav::route::Place;
use poinav_nav::{
    Building, CellState, Floor, GridOptions, NavError, NavOptions, Navigator, OccupancyGrid,
};
use poinav_poi::{classify, RobotProfile, RuleSet};

/// The model and IfcOpenShell's world vertices of its thin elements, by name.
fn model(dir: &Path) -> (Model, serde_json::Value) {
    let out = dir.join("thin.ifc");
    let py = poinav_testkit::python("ifcopenshell");
    let json = poinav_testkit::ifcos_with(&py, "author_thin.py", &[out.as_os_str()]);
    (Model::open(&out).unwrap(), json["elements"].clone())
}

/// The projected vertices IfcOpenShell meshes `name` with.
fn ifcos_points(elements: &serde_json::Value, name: &str) -> Vec<DVec2> {
    let v = elements[name]["vertices"].as_array().unwrap();
    assert!(!v.is_empty(), "IfcOpenShell meshes {name}");
    v.iter()
        .map(|p| DVec2::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect()
}

/// Points every centimetre along the polyline `line`.
fn along(line: &[DVec2]) -> Vec<DVec2> {
    let mut out = Vec::new();
    for w in line.windows(2) {
        let n = (w[0].distance(w[1]) / 0.01).ceil() as usize;
        out.extend((0..=n).map(|k| w[0].lerp(w[1], k as f64 / n as f64)));
    }
    out
}

/// Where each row of `grid`'s cells crosses the polyline `line` (each column, along a stretch
/// nearer horizontal than vertical): the cell holding such a point has its centre within half
/// a cell of the line, so when all of them are occupied no path of free cells crosses it.
fn crossings(grid: &OccupancyGrid, line: &[DVec2]) -> Vec<DVec2> {
    let res = grid.resolution_m;
    let mut out = Vec::new();
    for w in line.windows(2) {
        let (a, b) = (w[0], w[1]);
        let d = b - a;
        // Along y (rows) or x (columns), whichever the stretch changes more.
        let axis = usize::from(d.y.abs() >= d.x.abs());
        let (lo, hi) = (a[axis].min(b[axis]), a[axis].max(b[axis]));
        let o = grid.origin[axis];
        let mut k = ((lo - o) / res - 0.5).ceil();
        while o + (k + 0.5) * res <= hi {
            let t = (o + (k + 0.5) * res - a[axis]) / d[axis];
            out.push(a + d * t);
            k += 1.0;
        }
    }
    out
}

/// The states of the cells holding `points` in `grid`.
fn states(grid: &OccupancyGrid, points: &[DVec2]) -> Vec<CellState> {
    points
        .iter()
        .map(|p| grid.cells[grid.cell_of(*p).unwrap()])
        .collect()
}

fn grid(floor: &Floor, profile: &RobotProfile) -> OccupancyGrid {
    OccupancyGrid::build(floor, profile, &GridOptions::default()).unwrap()
}

fn item<'a>(plan: &'a FloorPlan, name: &str) -> Option<&'a poinav_geom::PlanItem> {
    plan.items.iter().find(|i| i.name.as_deref() == Some(name))
}

/// The route from `a` to `b` on the building's only storey: `Ok` or why not.
fn route(b: &Building, profile: &RobotProfile, a: DVec2, to: DVec2) -> Result<(), NavError> {
    let nav = Navigator::new(b, profile, &NavOptions::default()).unwrap();
    nav.route(
        &Place::point(None, a.x, a.y),
        &Place::point(None, to.x, to.y),
    )
    .map(|_| ())
}

#[test]
fn fences_surfaces_and_glass_panels_are_lines_no_route_crosses() {
    let dir = tempfile::tempdir().unwrap();
    let (model, ifcos) = model(dir.path());
    let profile = RobotProfile::paper();
    let stages = Stages::of(&model);
    assert!(
        stages.meshes.failures.is_empty(),
        "{:?}",
        stages.meshes.failures
    );
    let plan = &stages.plans[0];
    assert_eq!(stages.plans.len(), 1);
    assert!(plan.problems.is_empty(), "{:?}", plan.problems);

    // The plan: the surfaces are lines as wide as LINE_WIDTH_M with square ends; the glass is
    // its exact 5 mm strip; what is below or above the band is not there.
    let w = LINE_WIDTH_M;
    let fence = item(plan, "Fence").expect("the fence is in the plan");
    assert_eq!(
        (fence.kind, fence.source),
        (PlanItemKind::Obstacle, PlanSource::Section)
    );
    let want = (2.5 + w) * w + (3.0 + w) * w - w * w;
    assert!(
        (fence.area() - want).abs() < 1e-6,
        "{} {want}",
        fence.area()
    );
    let wall = item(plan, "Surface wall").expect("the surface wall is in the plan");
    assert_eq!(
        (wall.kind, wall.source),
        (PlanItemKind::Wall, PlanSource::Section)
    );
    let length = DVec2::new(2.8, 5.0).length();
    assert!(
        (wall.area() - (length + w) * w).abs() < 1e-6,
        "{}",
        wall.area()
    );
    let glass = item(plan, "Glass").expect("the glass is in the plan");
    assert!(
        (glass.area() - 4.0 * 0.005).abs() < 1e-6,
        "{}",
        glass.area()
    );
    assert!(item(plan, "Kick plate").is_none() && item(plan, "Transom").is_none());

    // The floor: the plan's regions as they are, not widened; IfcOpenShell's vertices of each
    // of the three on its obstacle.
    let c = classify(&model, &RuleSet::defaults(), &profile);
    let made = building(&model, &c, &stages);
    let floor = &made.building.floors[0];
    let rings = |name: &str| -> &Vec<polygon::Ring> {
        let id = &item(plan, name).unwrap().global_id;
        &floor.obstacles.iter().find(|o| &o.id == id).unwrap().rings
    };
    for name in ["Fence", "Surface wall", "Glass"] {
        let outers: Vec<&[DVec2]> = item(plan, name)
            .unwrap()
            .regions
            .iter()
            .map(|r| r.outer.as_slice())
            .collect();
        let floor_rings: Vec<&[DVec2]> = rings(name).iter().map(|r| &**r).collect();
        assert_eq!(floor_rings, outers, "{name}");
    }
    for name in ["Fence", "Surface wall", "Glass"] {
        for p in ifcos_points(&ifcos, name) {
            assert!(
                rings(name)
                    .iter()
                    .any(|r| polygon::contains(r, p) || polygon::boundary_distance(r, p) < 1e-6),
                "IfcOpenShell's vertex {p} of {name} is off its obstacle"
            );
        }
    }
    // IfcOpenShell's vertices lie on the lines the rooms are checked along.
    let fence_line = [
        DVec2::new(0.0, 2.0),
        DVec2::new(2.5, 2.0),
        DVec2::new(2.5, 5.0),
    ];
    let wall_line = [DVec2::new(4.6, 0.0), DVec2::new(7.4, 5.0)];
    let glass_line = [DVec2::new(8.0, 2.5025), DVec2::new(12.0, 2.5025)];
    let kick_line = [
        DVec2::new(12.0, 1.5),
        DVec2::new(14.0, 1.5),
        DVec2::new(16.0, 1.6),
    ];
    let transom_line = [DVec2::new(12.0, 3.5025), DVec2::new(16.0, 3.5025)];
    let off = |line: &[DVec2], p: DVec2| polygon::boundary_distance(line, p);
    for (name, line, tolerance) in [
        ("Fence", &fence_line[..], 1e-6),
        ("Surface wall", &wall_line[..], 1e-6),
        ("Glass", &glass_line[..], 0.0026),
        ("Kick plate", &kick_line[..], 1e-6),
        ("Transom", &transom_line[..], 0.0026),
    ] {
        // (A two-point "polygon" is its segment both ways; the L's closing side is far.)
        for p in ifcos_points(&ifcos, name) {
            let d = if line.len() == 3 {
                off(&line[..2], p).min(off(&line[1..], p))
            } else {
                off(line, p)
            };
            assert!(
                d <= tolerance,
                "{name}: IfcOpenShell's vertex {p} is {d} m off"
            );
        }
    }

    // The grid: every row (or column) of cells crossing the three has its cell on the line
    // occupied; along the kick plate and the transom, inside their room, every cell is free.
    let g = grid(floor, &profile);
    for (name, line, n) in [
        ("Fence", &fence_line[..], 110),
        ("Surface wall", &wall_line[..], 100),
        ("Glass", &glass_line[..], 80),
    ] {
        let points = crossings(&g, line);
        assert!(points.len() >= n, "{name}: {}", points.len());
        for (p, s) in points.iter().zip(states(&g, &points)) {
            assert_eq!(s, CellState::Occupied, "{name} at {p}");
        }
    }
    // Beside the door, in the wall's line, the sidelight's 5 mm pane is drawn whole, within
    // DOOR_MARGIN_M of the door's passage too (only doors', walls' and coverings' thin parts are
    // drawn by their centres there, `thin_cells::lines_doors`): the passage in the grid is as
    // wide as the door. (Drawn by its centres, none, the pane's first 0.25 m was free and the
    // passage looked a quarter of a metre wider.) The door's passage is crossed.
    let side_line = [DVec2::new(12.0, 2.0), DVec2::new(12.0, 2.6)];
    let points = crossings(&g, &side_line);
    assert_eq!(points.len(), 12, "{points:?}");
    for (p, s) in points.iter().zip(states(&g, &points)) {
        assert_eq!(s, CellState::Occupied, "Sidelight at {p}");
    }
    for p in ifcos_points(&ifcos, "Sidelight") {
        let d = polygon::boundary_distance(&side_line, p);
        assert!(
            d <= 0.0026,
            "Sidelight: IfcOpenShell's vertex {p} is {d} m off"
        );
    }
    route(
        &made.building,
        &profile,
        DVec2::new(10.0, 1.5),
        DVec2::new(13.5, 1.0),
    )
    .unwrap();
    let inside = |line: &[DVec2]| -> Vec<DVec2> {
        along(line)
            .into_iter()
            .filter(|p| p.x > 12.2 && p.x < 15.8)
            .collect()
    };
    for line in [&kick_line[..], &transom_line[..]] {
        let points = inside(line);
        assert!(points.len() > 300);
        assert!(states(&g, &points).iter().all(|s| *s == CellState::Free));
    }

    // No route crosses the three; the room with the panels below and above the band is
    // crossed.
    let trips = [
        (DVec2::new(1.0, 3.5), DVec2::new(3.2, 1.0)),
        (DVec2::new(4.8, 4.0), DVec2::new(7.2, 1.0)),
        (DVec2::new(10.0, 1.0), DVec2::new(10.0, 4.0)),
    ];
    let b = &made.building;
    for (a, to) in trips {
        let r = route(b, &profile, a, to);
        assert!(
            matches!(r, Err(NavError::Unreachable(_) | NavError::NoRoom(_))),
            "{a} -> {to}: {r:?}"
        );
    }
    route(b, &profile, DVec2::new(14.0, 0.8), DVec2::new(14.0, 4.2)).unwrap();

    // As they were drawn before: no fence, no surface wall, and the glass's exact strip holds
    // no cell centre (the grid's centres are on multiples of 5 cm plus 2.5 cm), so a grid of
    // centres alone left it free; without the three every route above exists.
    let g = grid(floor, &profile);
    let centres = (0..g.len())
        .filter(|&i| {
            let c = g.center(i);
            rings("Glass").iter().any(|r| polygon::contains(r, c))
        })
        .count();
    assert_eq!(centres, 0);
    let mut before = b.clone();
    let ids: Vec<String> = ["Fence", "Surface wall", "Glass"]
        .iter()
        .map(|n| item(plan, n).unwrap().global_id.clone())
        .collect();
    before.floors[0]
        .obstacles
        .retain(|o| !ids.iter().any(|i| o.id == *i));
    for (a, to) in trips {
        route(&before, &profile, a, to).unwrap();
    }
}

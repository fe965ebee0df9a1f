//! Routes on hand-made floors: every pair of rooms joined by accessible doors has a route whose
//! length is within 5% of the grid's shortest path (an independent Dijkstra here), doors passed
//! in order, role slow-downs in the time, unreachable goals naming the blocking door, and
//! routes across storeys through lifts (stairs only for legged profiles).

mod support;

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use glam::DVec2;
use poinav_nav::{Building, NavError, NavGrid, NavOptions, Navigator, Place, Route};
use poinav_poi::{Locomotion, RobotProfile};
use support::{demo, demo_floor, office_floor, two_storeys};

/// Shortest 8-connected path length (metres) between two cells over traversable cells: plain
/// Dijkstra with integer costs (1e6 per axis step, 1414214 per diagonal).
fn grid_shortest(grid: &NavGrid, start: usize, goal: usize) -> f64 {
    let g = &grid.occupancy;
    let (w, h) = (g.width as i64, g.height as i64);
    let axis = 1_000_000u64;
    let diag = (std::f64::consts::SQRT_2 * 1e6).round() as u64;
    let mut dist = vec![u64::MAX; g.len()];
    let mut heap = BinaryHeap::new();
    dist[start] = 0;
    heap.push(Reverse((0u64, start)));
    while let Some(Reverse((d, i))) = heap.pop() {
        if i == goal {
            return d as f64 / 1e6 * g.resolution_m;
        }
        if d > dist[i] {
            continue;
        }
        let (c, r) = ((i as i64) % w, (i as i64) / w);
        for dr in -1..=1_i64 {
            for dc in -1..=1_i64 {
                if dr == 0 && dc == 0 {
                    continue;
                }
                let (nc, nr) = (c + dc, r + dr);
                if nc < 0 || nr < 0 || nc >= w || nr >= h {
                    continue;
                }
                let j = (nr * w + nc) as usize;
                if !grid.traversable(j) {
                    continue;
                }
                let nd = d + if dc != 0 && dr != 0 { diag } else { axis };
                if nd < dist[j] {
                    dist[j] = nd;
                    heap.push(Reverse((nd, j)));
                }
            }
        }
    }
    f64::INFINITY
}

/// The route's length over the grid's shortest path between its end cells.
fn ratio(nav: &Navigator<'_>, route: &Route) -> f64 {
    let leg = &route.legs[0];
    let grid = &nav.floors[leg.floor].grid;
    let p0 = leg.polyline[0];
    let p1 = *leg.polyline.last().unwrap();
    let a = grid.occupancy.cell_of(DVec2::new(p0[0], p0[1])).unwrap();
    let b = grid.occupancy.cell_of(DVec2::new(p1[0], p1[1])).unwrap();
    route.length_m / grid_shortest(grid, a, b)
}

fn door_names(route: &Route) -> Vec<String> {
    route
        .doors
        .iter()
        .map(|d| d.name.clone().unwrap())
        .collect()
}

#[test]
fn room_1_to_room_6_is_within_5_percent_of_the_grid_shortest_path() {
    let building = Building::single(demo());
    let profile = RobotProfile::paper();
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    let route = nav
        .route(&Place::zone("Room 1"), &Place::zone("Room 6"))
        .unwrap();
    let r = ratio(&nav, &route);
    println!(
        "Room 1 -> Room 6: {:.3} m, {:.3} s, {} points, ratio to the grid's shortest path {r:.4}",
        route.length_m,
        route.time_s,
        route.legs[0].polyline.len()
    );
    assert!((0.95..=1.05).contains(&r), "ratio {r}");
    assert_eq!(door_names(&route), ["Door Room 1", "Door Room 6"]);
    assert_eq!(route.legs[0].zones, ["Room 1", "Corridor", "Room 6"]);
    assert!(route.legs[0].guided);
    // From the middle of Room 1 (2, 2) to the middle of Room 6 (10.4, 8.8): at least the
    // straight line's length; in a corridor at half speed (C-1 SPEED_REDUCTION).
    assert!(route.length_m >= DVec2::new(2.0, 2.0).distance(DVec2::new(10.4, 8.8)));
    assert!(route.length_m < 16.0);
    assert!(route.time_s > route.length_m / 5.0);
    let leg = &route.legs[0];
    assert!((route.time_s - leg.travel_time_s - leg.turn_time_s).abs() < 1e-6);
}

#[test]
fn every_pair_of_rooms_has_a_route_within_5_percent() {
    let building = Building::single(demo());
    let profile = RobotProfile::paper();
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    let (mut lo, mut hi): (f64, f64) = (1.0, 0.0);
    for a in 1..=6 {
        for b in 1..=6 {
            if a == b {
                continue;
            }
            let (from, to) = (format!("Room {a}"), format!("Room {b}"));
            let route = nav.route(&Place::zone(&from), &Place::zone(&to)).unwrap();
            let r = ratio(&nav, &route);
            (lo, hi) = (lo.min(r), hi.max(r));
            assert!((0.95..=1.05).contains(&r), "{from} -> {to}: ratio {r}");
            assert_eq!(
                door_names(&route),
                [format!("Door {from}"), format!("Door {to}")],
                "{from} -> {to}"
            );
        }
    }
    println!("demo building, 30 routes: length ratios {lo:.4} to {hi:.4}");
    // Without the clearance penalty the routes are the shortest: never longer than the
    // 8-connected grid path, shorter where they run diagonally (an 8-connected path can be up
    // to 8.2% longer than the straight line, so the ratio can go down to 0.924).
    let options = NavOptions {
        inflation: poinav_nav::InflationOptions {
            penalty: 0.0,
            ..Default::default()
        },
        ..Default::default()
    };
    let nav = Navigator::new(&building, &profile, &options).unwrap();
    let (mut lo, mut hi): (f64, f64) = (1.0, 0.0);
    for a in 1..=6 {
        for b in (1..=6).filter(|b| *b != a) {
            let route = nav
                .route(
                    &Place::zone(&format!("Room {a}")),
                    &Place::zone(&format!("Room {b}")),
                )
                .unwrap();
            let r = ratio(&nav, &route);
            (lo, hi) = (lo.min(r), hi.max(r));
        }
    }
    println!("without the clearance penalty: ratios {lo:.4} to {hi:.4}");
    assert!(lo >= 0.924 && hi <= 1.0 + 1e-9, "{lo} {hi}");
}

#[test]
fn restricted_door_slows_the_route() {
    // Room 2's 0.80 m door is RESTRICTED (B-2): the route into Room 2 passes it at half speed.
    let building = Building::single(demo());
    let profile = RobotProfile::paper();
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    let to2 = nav
        .route(&Place::zone("Room 1"), &Place::zone("Room 2"))
        .unwrap();
    assert_eq!(door_names(&to2), ["Door Room 1", "Door Room 2"]);
    assert_eq!(to2.doors[1].status.label(), "RESTRICTED");
    let wide = Building::single(demo_floor(&poinav_author::DemoBuilding {
        room2_door_width_m: 1.2,
        ..Default::default()
    }));
    let nav_wide = Navigator::new(&wide, &profile, &NavOptions::default()).unwrap();
    let to2_wide = nav_wide
        .route(&Place::zone("Room 1"), &Place::zone("Room 2"))
        .unwrap();
    // Same way; passing the 0.2 m deep door at 2.5 instead of 5.0 m/s costs at least 0.02 s.
    let dt =
        (to2.time_s - to2.legs[0].turn_time_s) - (to2_wide.time_s - to2_wide.legs[0].turn_time_s);
    let dl = to2.length_m - to2_wide.length_m;
    println!("0.80 m vs 1.20 m door: {dt:.4} s slower, {dl:.4} m longer");
    assert!(dt > 0.015, "{dt}");
}

#[test]
fn narrowed_room_2_door_names_the_door() {
    let building = Building::single(demo_floor(&poinav_author::DemoBuilding {
        room2_door_width_m: 0.6,
        ..Default::default()
    }));
    let profile = RobotProfile::paper();
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    let err = nav
        .route(&Place::zone("Room 1"), &Place::zone("Room 2"))
        .unwrap_err();
    let NavError::Unreachable(u) = &err else {
        panic!("{err}");
    };
    assert_eq!(u.blocking.len(), 1);
    assert_eq!(u.blocking[0].name.as_deref(), Some("Door Room 2"));
    assert_eq!(u.blocking[0].status.label(), "BLOCKED");
    let text = err.to_string();
    assert!(text.contains("Door Room 2"), "{text}");
    assert!(
        text.contains("clear width 0.600 m < robot width 0.700 m"),
        "{text}"
    );
    // The other rooms are unaffected.
    assert!(nav
        .route(&Place::zone("Room 1"), &Place::zone("Room 3"))
        .is_ok());
}

#[test]
fn office_routes_across_the_hall_and_around_hazards() {
    let building = Building::single(office_floor());
    let profile = RobotProfile::paper();
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    // Office 1 (south-west) to Office 98 (north-east) through corridor A, the hall, corridor B.
    let t0 = std::time::Instant::now();
    let route = nav
        .route(&Place::zone("Office 1"), &Place::zone("Office 98"))
        .unwrap();
    let elapsed = t0.elapsed().as_secs_f64();
    let r = ratio(&nav, &route);
    println!(
        "Office 1 -> Office 98: {:.2} m, {:.2} s, ratio {r:.4}, planned in {elapsed:.3} s",
        route.length_m, route.time_s
    );
    assert!((0.95..=1.05).contains(&r), "ratio {r}");
    assert_eq!(
        route.legs[0].zones,
        ["Office 1", "Corridor A", "Hall", "Corridor B", "Office 98"]
    );
    assert_eq!(door_names(&route), ["Door Office 1", "Door Office 98"]);
    // Office 50's door is 0.60 m: BLOCKED, named.
    let err = nav
        .route(&Place::zone("Office 1"), &Place::zone("Office 50"))
        .unwrap_err();
    assert!(err.to_string().contains("Door Office 50"), "{err}");
    // From the west entrance (a point in its passage) to an office.
    let route = nav
        .route(&Place::point(None, -0.1, 10.2), &Place::zone("Office 3"))
        .unwrap();
    assert_eq!(door_names(&route), ["Entrance West", "Door Office 3"]);
}

#[test]
fn across_storeys_by_lift_or_by_stairs_for_legged_robots() {
    let profile = RobotProfile::paper();
    let building = two_storeys(true);
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    let from = "Room 1@Ground floor".parse::<Place>().unwrap();
    let to = "Room 6@First floor".parse::<Place>().unwrap();
    let route = nav.route(&from, &to).unwrap();
    assert_eq!(route.legs.len(), 2);
    assert_eq!(route.connections.len(), 1);
    assert_eq!(route.connections[0].name.as_deref(), Some("Lift"));
    // 30 s wait + 3.5 m at 1 m/s.
    assert!((route.connections[0].time_s - 33.5).abs() < 1e-6);
    let legs: f64 = route
        .legs
        .iter()
        .map(|l| l.travel_time_s + l.turn_time_s)
        .sum();
    assert!((route.time_s - legs - 33.5).abs() < 1e-5);
    println!(
        "Room 1 -> Room 6 one floor up by lift: {:.2} m, {:.2} s",
        route.length_m, route.time_s
    );

    // No lift: a wheeled robot cannot climb the stairs, which are named.
    let building = two_storeys(false);
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    let err = nav.route(&from, &to).unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("Stair") && text.contains("stairs are not passable"),
        "{text}"
    );
    // A legged robot takes them.
    let mut legged = profile.clone();
    legged.locomotion = Locomotion::Legged;
    let nav = Navigator::new(&building, &legged, &NavOptions::default()).unwrap();
    let route = nav.route(&from, &to).unwrap();
    assert_eq!(route.connections[0].kind, "stair");
    assert!((route.connections[0].time_s - 17.5).abs() < 1e-6);
}

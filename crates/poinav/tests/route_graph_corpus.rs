//! The Nav2 route graphs of every multi-storey corpus building (issue 20, item 3), read back
//! as nav2_route's GeoJSON loader reads them: ids unique across nodes and edges, every edge
//! both ways, each storey's nodes in its own frame. Every edge's speed limit and operations
//! are checked against the POI roles of the spaces and doors it crosses, worked out here from
//! the roles themselves (B-1 and B-2 halve the speed, C-1 by its protocol, a RESTRICTED door
//! is narrow), not by poinav's speed code; every door crossed asks for an `OpenDoor`
//! `TriggerEvent` on entry, naming the door. A* written here over the building-wide graph
//! then visits the same rooms in the same order as `poinav route` between pairs of rooms, on
//! one storey and across storeys (office-a's lift for the paper robot, stairs for a legged
//! one).

mod common;

use std::cmp::Reverse;
use std::collections::{BTreeMap, BTreeSet, BinaryHeap};
use std::path::Path;

use glam::DVec2;
use poinav_ifc::Model;
use poinav_nav::nav2::{write_navigator_bundle, BundleSummary, Nav2Options};
use poinav_nav::{Building, NavError, NavOptions, Navigator, Place};
use poinav_poi::{
    classify, AccessibilityStatus, CoordinationProtocol, Locomotion, RobotProfile, Role, RuleSet,
};
use serde_json::Value;

/// A graph file as nav2_route loads it.
struct Graph {
    /// id -> node feature properties and position.
    nodes: BTreeMap<u64, (DVec2, Value)>,
    /// id -> edge properties.
    edges: BTreeMap<u64, Value>,
    /// node -> (end, cost, edge id).
    out: BTreeMap<u64, Vec<(u64, f64, u64)>>,
}

fn has_null(v: &Value) -> bool {
    match v {
        Value::Null => true,
        Value::Object(m) => m.values().any(has_null),
        Value::Array(a) => a.iter().any(has_null),
        _ => false,
    }
}

fn load_graph(path: &Path) -> Graph {
    let text = std::fs::read_to_string(path).unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["type"], "FeatureCollection");
    let mut ids = BTreeSet::new();
    let (mut nodes, mut edges, mut out) = (BTreeMap::new(), BTreeMap::new(), BTreeMap::new());
    for f in json["features"].as_array().unwrap() {
        let p = &f["properties"];
        // The loader takes numbers, booleans, strings, arrays and objects; a null fails it.
        assert!(!has_null(p), "{}: a null in {p}", path.display());
        let id = p["id"].as_u64().unwrap();
        assert!(ids.insert(id), "{}: id {id} twice", path.display());
        match f["geometry"]["type"].as_str().unwrap() {
            "Point" => {
                let c = &f["geometry"]["coordinates"];
                let at = DVec2::new(c[0].as_f64().unwrap(), c[1].as_f64().unwrap());
                nodes.insert(id, (at, p.clone()));
            }
            "MultiLineString" => {
                edges.insert(id, p.clone());
            }
            other => panic!("geometry {other}"),
        }
    }
    for (&id, p) in &edges {
        let (s, e) = (p["startid"].as_u64().unwrap(), p["endid"].as_u64().unwrap());
        assert!(
            nodes.contains_key(&s) && nodes.contains_key(&e),
            "edge {id}"
        );
        let cost = p["cost"].as_f64().unwrap();
        assert!(cost >= 0.0, "edge {id} cost {cost}");
        out.entry(s).or_insert_with(Vec::new).push((e, cost, id));
    }
    let directed: BTreeSet<(u64, u64)> = edges
        .values()
        .map(|p| (p["startid"].as_u64().unwrap(), p["endid"].as_u64().unwrap()))
        .collect();
    for (s, e) in &directed {
        assert!(directed.contains(&(*e, *s)), "edge {s}->{e} has no reverse");
    }
    Graph { nodes, edges, out }
}

/// The speed fraction of a space from its POI roles (default role speeds).
fn zone_fraction(roles: &[Role], protocol: Option<CoordinationProtocol>) -> f64 {
    let mut f: f64 = 1.0;
    if roles.contains(&Role::Hazard) || roles.contains(&Role::Narrow) {
        f = 0.5;
    }
    if roles.contains(&Role::MultiRobotZone)
        && protocol == Some(CoordinationProtocol::SpeedReduction)
    {
        f = f.min(0.5);
    }
    f
}

/// The speed fraction of a door: narrow (B-2) or RESTRICTED halves it.
fn door_fraction(roles: &[Role], status: AccessibilityStatus) -> f64 {
    if roles.contains(&Role::Narrow) || status == AccessibilityStatus::Restricted {
        0.5
    } else {
        1.0
    }
}

/// A ROS 2 service name: `/`-separated tokens of letters, digits and `_`, none starting with
/// a digit, no `__`.
fn ros_name(s: &str) -> bool {
    s.starts_with('/')
        && !s.contains("__")
        && s[1..].split('/').all(|t| {
            !t.is_empty()
                && !t.starts_with(|c: char| c.is_ascii_digit())
                && t.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        })
}

#[derive(Default, Debug)]
struct Tally {
    edges: usize,
    slowed: usize,
    door_ops: usize,
    lift_ops: usize,
    storey_links: usize,
}

/// Checks one storey's (or the building's) edges against the roles of what they cross.
fn check_edges(graph: &Graph, building: &Building, nav: &Navigator<'_>, tally: &mut Tally) {
    let vmax = nav.profile.max_speed_m_s;
    for (id, p) in &graph.edges {
        let m = &p["metadata"];
        let start = &graph.nodes[&p["startid"].as_u64().unwrap()].1["metadata"];
        let end = &graph.nodes[&p["endid"].as_u64().unwrap()].1["metadata"];
        let ops: Vec<&Value> = p["operations"]
            .as_object()
            .map(|o| o.values().collect())
            .unwrap_or_default();
        for op in &ops {
            assert!(op["type"].is_string() && op["metadata"].is_object(), "{op}");
            assert_eq!(op["trigger"], "ON_ENTER", "{op}");
            assert!(
                ros_name(op["metadata"]["service_name"].as_str().unwrap()),
                "{op}"
            );
        }
        if let Some(kind) = m["connection"].as_str() {
            // An edge joining storeys: landing to landing of the same connection.
            tally.storey_links += 1;
            assert_eq!(start["kind"], "landing");
            assert_eq!(end["kind"], "landing");
            assert_eq!(start["element"], m["element"]);
            assert_eq!(end["element"], m["element"]);
            assert_eq!(start["connection"], kind);
            assert_ne!(start["storey"], end["storey"]);
            assert_eq!(m["from_storey"], start["storey"]);
            assert_eq!(m["to_storey"], end["storey"]);
            assert_eq!(p["overridable"], false);
            let c = building
                .connections
                .iter()
                .find(|c| c.id.as_str() == m["element"])
                .unwrap();
            assert_eq!(c.kind.label(), kind);
            let fi = |name: &Value| building.floor_index(name.as_str().unwrap()).unwrap();
            let dz = building.floors[fi(&m["from_storey"])].elevation_m
                - building.floors[fi(&m["to_storey"])].elevation_m;
            let time = c.travel_time_s(dz, &nav.profile);
            assert!((p["cost"].as_f64().unwrap() - time).abs() < 1e-5, "{p}");
            let lift: Vec<&&Value> = ops.iter().filter(|o| o["type"] == "CallLift").collect();
            assert_eq!(lift.len(), usize::from(kind == "lift"), "{p}");
            for o in lift {
                assert_eq!(o["metadata"]["lift_id"], m["element"]);
                assert_eq!(o["metadata"]["to_storey"], m["to_storey"]);
                tally.lift_ops += 1;
            }
            continue;
        }
        tally.edges += 1;
        let fi = start["storey_index"].as_u64().unwrap() as usize;
        assert_eq!(end["storey_index"], start["storey_index"], "edge {id}");
        let floor = &building.floors[fi];
        assert_eq!(start["storey"], floor.name.as_str());
        // The slowest fraction of the spaces and doors crossed, from their roles.
        let mut slowest: f64 = 1.0;
        let mut roles_seen: BTreeSet<String> = BTreeSet::new();
        for z in m["zones"].as_array().unwrap() {
            let zone = floor.zones.iter().find(|x| x.id.as_str() == *z).unwrap();
            slowest = slowest.min(zone_fraction(&zone.roles, zone.coordination.map(|c| c.1)));
            for r in &zone.roles {
                if matches!(r, Role::Hazard | Role::Narrow | Role::MultiRobotZone) {
                    roles_seen.insert(r.label().to_string());
                }
            }
        }
        let mut expected_doors = BTreeSet::new();
        for d in m["doors"].as_array().unwrap() {
            let k = floor
                .doors
                .iter()
                .position(|x| x.id.as_str() == *d)
                .unwrap();
            let door = &floor.doors[k];
            let status = nav.floors[fi].grid.occupancy.doors[k].status;
            let f = door_fraction(&door.roles, status);
            if f < 1.0 {
                roles_seen.insert("B-2".into());
            }
            slowest = slowest.min(f);
            let leaving = start["kind"] == "door" && start["element"] == *d;
            if !door.doorless && !leaving {
                expected_doors.insert(door.id.to_string());
            }
        }
        let limit = m["speed_limit"].as_f64().unwrap();
        assert!(m["speed_limit"].is_f64(), "edge {id}: speed_limit a float");
        assert_eq!(limit, (slowest * 100.0).round(), "edge {id}: {m}");
        if limit < 100.0 {
            tally.slowed += 1;
        }
        // The roles named are those of what the edge crosses (C-1 with its protocol).
        let named: BTreeSet<String> = m["speed_roles"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| {
                let r = r.as_str().unwrap();
                r.split(' ').next().unwrap().to_string()
            })
            .collect();
        assert_eq!(named, roles_seen, "edge {id}: {m}");
        // Cost: seconds between the full speed and the slowest speed over the length.
        let len = m["length_m"].as_f64().unwrap();
        let cost = p["cost"].as_f64().unwrap();
        assert!(
            cost >= len / vmax - 1e-5 && cost <= len / (vmax * slowest) + 1e-5,
            "edge {id}: cost {cost} for {len} m at {slowest}"
        );
        // One OpenDoor on entry per door crossed, naming it.
        let opened: BTreeSet<String> = ops
            .iter()
            .filter(|o| o["type"] == "OpenDoor")
            .map(|o| o["metadata"]["door_id"].as_str().unwrap().to_string())
            .collect();
        assert_eq!(opened, expected_doors, "edge {id}: {p}");
        assert_eq!(ops.len(), opened.len(), "edge {id}: only door operations");
        tally.door_ops += opened.len();
    }
}

/// A* over `graph` (heuristic: straight distance at full speed on the goal's storey, 0 on
/// others), returning the edges of the cheapest way from `from` to `to`.
fn astar(graph: &Graph, from: u64, to: u64, vmax: f64) -> Option<Vec<u64>> {
    let (goal_at, goal) = &graph.nodes[&to];
    let storey = |n: u64| graph.nodes[&n].1["metadata"]["storey_index"].clone();
    let h = |n: u64| {
        if storey(n) == goal["metadata"]["storey_index"] {
            graph.nodes[&n].0.distance(*goal_at) / vmax
        } else {
            0.0
        }
    };
    let key = |c: f64| (c * 1e6).round() as u64;
    let mut best: BTreeMap<u64, f64> = BTreeMap::from([(from, 0.0)]);
    let mut via: BTreeMap<u64, u64> = BTreeMap::new();
    let mut heap = BinaryHeap::from([Reverse((key(h(from)), from))]);
    let mut closed = BTreeSet::new();
    while let Some(Reverse((_, n))) = heap.pop() {
        if n == to {
            let mut path = Vec::new();
            let mut at = to;
            while at != from {
                let e = via[&at];
                path.push(e);
                at = graph.edges[&e]["startid"].as_u64().unwrap();
            }
            path.reverse();
            return Some(path);
        }
        if !closed.insert(n) {
            continue;
        }
        for &(m, cost, e) in graph.out.get(&n).into_iter().flatten() {
            let g = best[&n] + cost;
            if best.get(&m).is_none_or(|&b| g < b) {
                best.insert(m, g);
                via.insert(m, e);
                heap.push(Reverse((key(g + h(m)), m)));
            }
        }
    }
    None
}

/// Rooms in order along edges (consecutive repeats merged).
fn rooms_of(graph: &Graph, edges: &[u64]) -> Vec<String> {
    let mut rooms: Vec<String> = Vec::new();
    for e in edges {
        for z in graph.edges[e]["metadata"]["zone_names"]
            .as_array()
            .into_iter()
            .flatten()
        {
            let z = z.as_str().unwrap().to_string();
            if rooms.last() != Some(&z) {
                rooms.push(z);
            }
        }
    }
    rooms
}

struct Outcome {
    pairs: usize,
    same: usize,
    across: usize,
    unreachable: usize,
    mismatches: Vec<String>,
}

/// Compares A* over the building graph with `poinav route` for room pairs: per storey its
/// first, middle and last rooms (by graph id), and the first rooms of consecutive storeys.
fn compare_routes(graph: &Graph, nav: &Navigator<'_>, name: &str) -> Outcome {
    let mut by_storey: BTreeMap<u64, Vec<(u64, String)>> = BTreeMap::new();
    for (&id, (_, p)) in &graph.nodes {
        let m = &p["metadata"];
        if m["kind"] == "zone" {
            by_storey
                .entry(m["storey_index"].as_u64().unwrap())
                .or_default()
                .push((id, m["element"].as_str().unwrap().to_string()));
        }
    }
    let mut pairs = Vec::new();
    let firsts: Vec<&(u64, String)> = by_storey.values().map(|z| &z[0]).collect();
    for zones in by_storey.values() {
        let n = zones.len();
        for (a, b) in [(0, n - 1), (0, n / 2), (n / 2, n - 1)] {
            if a != b {
                pairs.push((zones[a].clone(), zones[b].clone()));
            }
        }
    }
    for w in firsts.windows(2) {
        pairs.push((w[0].clone(), w[1].clone()));
    }
    pairs.sort();
    pairs.dedup();
    let mut out = Outcome {
        pairs: 0,
        same: 0,
        across: 0,
        unreachable: 0,
        mismatches: Vec::new(),
    };
    for ((ga, ea), (gb, eb)) in pairs {
        let found = astar(graph, ga, gb, nav.profile.max_speed_m_s);
        let route = nav.route(&Place::zone(&ea), &Place::zone(&eb));
        out.pairs += 1;
        match (found, route) {
            (Some(edges), Ok(r)) => {
                let mut rooms: Vec<String> = Vec::new();
                for z in r.legs.iter().flat_map(|l| l.zones.iter()) {
                    if rooms.last() != Some(z) {
                        rooms.push(z.clone());
                    }
                }
                let graph_rooms = rooms_of(graph, &edges);
                if !r.connections.is_empty() {
                    out.across += 1;
                }
                if graph_rooms == rooms {
                    out.same += 1;
                } else {
                    out.mismatches.push(format!(
                        "{name} {ea} -> {eb}: graph {graph_rooms:?}, route {rooms:?}"
                    ));
                }
            }
            (None, Err(NavError::Unreachable(_) | NavError::NoRoom(_))) => out.unreachable += 1,
            (g, r) => out.mismatches.push(format!(
                "{name} {ea} -> {eb}: graph {:?}, route {:?}",
                g.map(|e| rooms_of(graph, &e)),
                r.map(|r| r.legs.len())
            )),
        }
    }
    out
}

/// Writes the bundle and checks every graph in it; returns the tally and the building graph.
fn check_bundle(
    building: &Building,
    profile: &RobotProfile,
    dir: &Path,
) -> (BundleSummary, Tally, Graph) {
    // As `write_bundle` does (the navigator crops each storey to its extent).
    let options = Nav2Options::default();
    let nav = Navigator::new(building, profile, &options.nav).unwrap();
    let summary = write_navigator_bundle(&nav, &options, dir).unwrap();
    let mut tally = Tally::default();
    let whole = load_graph(&dir.join("route_graph.geojson"));
    let mut total_nodes = 0;
    for st in &summary.storeys {
        let g = load_graph(&dir.join(&st.folder).join("route_graph.geojson"));
        assert_eq!(g.nodes.len(), st.graph_nodes);
        assert_eq!(g.edges.len(), st.graph_edges);
        total_nodes += g.nodes.len();
        for (_, p) in g.nodes.values() {
            assert_eq!(p["frame"], "map");
            assert_eq!(p["metadata"]["storey"], st.floor.as_str());
        }
        check_edges(&g, building, &nav, &mut tally);
    }
    // The building graph: every storey's nodes, each in its storey's frame.
    assert_eq!(whole.nodes.len(), total_nodes);
    assert_eq!(whole.nodes.len(), summary.building_graph.nodes);
    assert_eq!(whole.edges.len(), summary.building_graph.edges);
    for (_, p) in whole.nodes.values() {
        let st = summary
            .storeys
            .iter()
            .find(|s| s.floor == p["metadata"]["storey"])
            .unwrap();
        let frame = format!("map_{}", st.folder.replace('-', "_"));
        assert_eq!(p["frame"], frame.as_str());
        assert_eq!(p["metadata"]["frame"], frame.as_str());
        if p["metadata"]["kind"] != "waypoint" {
            assert!(p["metadata"]["element"].is_string(), "{p}");
        }
    }
    let mut building_tally = Tally::default();
    check_edges(&whole, building, &nav, &mut building_tally);
    assert_eq!(building_tally.edges, tally.edges);
    assert_eq!(
        building_tally.storey_links,
        summary.building_graph.storey_links
    );
    tally.storey_links = building_tally.storey_links;
    tally.lift_ops = building_tally.lift_ops;
    (summary, tally, whole)
}

#[test]
fn corpus_route_graphs_carry_the_roles_operations_and_the_routes_rooms() {
    let paper = RobotProfile::paper();
    let legged = RobotProfile {
        locomotion: Locomotion::Legged,
        ..RobotProfile::paper()
    };
    let dir = tempfile::tempdir().unwrap();
    let mut report = Vec::new();
    let mut mismatches = Vec::new();
    // Room pairs with the same rooms, of them across storeys, door operations, slowed edges.
    let mut totals = (0, 0, 0, 0);
    for file in [
        "office-a.ifc",
        "fzk-haus-ifc4.ifc",
        "fzk-haus-ifc4x3.ifc",
        "duplex-apartment.ifc",
        "institute-var-2.ifc",
        "ifc4-test-model.ifc",
        "wall-door-column-ifc4x3.ifc",
        "revit-japanese-x2.ifc",
    ] {
        let clock = std::time::Instant::now();
        let model = Model::open(poinav_testkit::corpus_file(file)).unwrap();
        let c = classify(&model, &RuleSet::defaults(), &paper);
        let building =
            poinav_bridge::building(&model, &c, &poinav_bridge::Stages::of(&model)).building;
        assert!(building.floors.len() >= 2, "{file}: a multi-storey model");
        let built = clock.elapsed().as_secs_f64();
        for profile in [&paper, &legged] {
            // A legged robot where there are stairs (office-a's lift is enough there: its
            // stairs would double the time for no new kind of edge).
            if profile.climbs_stairs()
                && (file == "office-a.ifc"
                    || !building
                        .connections
                        .iter()
                        .any(|c| c.kind == poinav_nav::ConnectionKind::Stair))
            {
                continue;
            }
            let started = std::time::Instant::now();
            let key = format!("{file} {:?}", profile.locomotion);
            let out = dir.path().join(key.replace([' ', '.'], "_"));
            let (summary, tally, whole) = check_bundle(&building, profile, &out);
            let nav = Navigator::new(&building, profile, &NavOptions::default()).unwrap();
            let outcome = compare_routes(&whole, &nav, &key);
            report.push(format!(
                "{key}: {} storeys, {} nodes, {} edges ({} slowed, {} door operations), {} storey links ({} lift operations); {} room pairs: {} same rooms ({} across storeys), {} unreachable both ways",
                summary.storeys.len(),
                summary.building_graph.nodes,
                summary.building_graph.edges,
                tally.slowed,
                tally.door_ops,
                tally.storey_links,
                tally.lift_ops,
                outcome.pairs,
                outcome.same,
                outcome.across,
                outcome.unreachable,
            ));
            mismatches.extend(outcome.mismatches.iter().cloned());
            totals.0 += outcome.same;
            totals.1 += outcome.across;
            totals.2 += tally.door_ops;
            totals.3 += tally.slowed;
            if file == "office-a.ifc" {
                // The lift, both ways, each calling it.
                assert_eq!((tally.storey_links, tally.lift_ops), (2, 2), "{key}");
            }
            if profile.climbs_stairs() {
                assert!(tally.storey_links >= 2, "{key}: stairs join storeys");
            }
            report.push(format!(
                "  building {built:.1} s, bundle and routes {:.1} s",
                started.elapsed().as_secs_f64()
            ));
        }
    }
    println!("{}", report.join("\n"));
    println!("totals (same rooms, across storeys, door operations, slowed edges): {totals:?}");
    assert!(mismatches.is_empty(), "{}", mismatches.join("\n"));
    // When written: 55 pairs with the same rooms (7 across storeys), 1,306 door operations,
    // 3,604 slowed edges.
    assert!(totals.0 >= 45 && totals.1 >= 5, "{totals:?}");
    assert!(totals.2 >= 1000 && totals.3 >= 3000, "{totals:?}");
}

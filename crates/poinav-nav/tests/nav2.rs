//! The Nav2 bundle read back by an independent reader written from nav2_map_server's rules
//! (FIELD-NOTES "Nav2 conventions"): YAML fields, binary PGM, p = (255 - x) / 255, trinary and
//! scale thresholds, first image row = largest y; the masks' values through the filter info
//! (value = base + multiplier * mask); the route graph's ids, directions and collision-free
//! edges.

mod support;

use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::path::Path;

use glam::DVec2;
use poinav_nav::grid::CellState;
use poinav_nav::nav2::{write_bundle, Nav2Options};
use poinav_nav::{Building, NavOptions, Navigator, RoleSpeeds};
use poinav_poi::RobotProfile;
use serde_json::Value;
use support::{demo, demo_floor, office_floor, two_storeys};

/// `key: value` lines of a flat YAML file.
fn read_yaml(path: &Path) -> BTreeMap<String, String> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim_start().starts_with('#'))
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_string(), v.trim().trim_matches('"').to_string()))
        .collect()
}

/// A binary PGM (P5, maxval 255): width, height, pixels row by row from the top.
fn read_pgm(path: &Path) -> (usize, usize, Vec<u8>) {
    let pgm = poinav_testkit::read_pgm(&std::fs::read(path).unwrap());
    assert_eq!(pgm.maxval, 255);
    (pgm.width, pgm.height, pgm.pixels)
}

/// An occupancy grid as nav2_map_server loads it: cell values (-1 unknown, 0-100) with row 0 at
/// the bottom, resolution and origin.
struct Loaded {
    width: usize,
    height: usize,
    resolution: f64,
    origin: [f64; 3],
    data: Vec<i8>,
}

impl Loaded {
    fn at(&self, x: f64, y: f64) -> i8 {
        let c = ((x - self.origin[0]) / self.resolution).floor() as usize;
        let r = ((y - self.origin[1]) / self.resolution).floor() as usize;
        self.data[r * self.width + c]
    }
}

fn load(yaml_path: &Path) -> Loaded {
    let y = read_yaml(yaml_path);
    let image = yaml_path.parent().unwrap().join(&y["image"]);
    let resolution: f64 = y["resolution"].parse().unwrap();
    let origin: Vec<f64> = y["origin"]
        .trim_matches(|c| c == '[' || c == ']')
        .split(',')
        .map(|v| v.trim().parse().unwrap())
        .collect();
    let negate: i32 = y["negate"].parse().unwrap();
    let occ_t: f64 = y["occupied_thresh"].parse().unwrap();
    let free_t: f64 = y["free_thresh"].parse().unwrap();
    let mode = y.get("mode").map_or("trinary", String::as_str).to_string();
    let (w, h, pixels) = read_pgm(&image);
    let mut data = vec![0i8; w * h];
    for row in 0..h {
        for col in 0..w {
            let x = f64::from(pixels[row * w + col]);
            let shade = x / 255.0;
            let p = if negate != 0 { shade } else { 1.0 - shade };
            let v: i8 = match mode.as_str() {
                "trinary" => {
                    if p > occ_t {
                        100
                    } else if p < free_t {
                        0
                    } else {
                        -1
                    }
                }
                "scale" => {
                    if p > occ_t {
                        100
                    } else if p < free_t {
                        0
                    } else {
                        ((p - free_t) / (occ_t - free_t) * 100.0).round_ties_even() as i8
                    }
                }
                other => panic!("mode {other}"),
            };
            data[w * (h - row - 1) + col] = v;
        }
    }
    Loaded {
        width: w,
        height: h,
        resolution,
        origin: [origin[0], origin[1], origin[2]],
        data,
    }
}

/// base and multiplier per costmap_filter_info_server in the params file.
fn filter_info(path: &Path) -> BTreeMap<String, (i32, f64, f64)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut out = BTreeMap::new();
    let mut server = String::new();
    let mut vals: BTreeMap<String, String> = BTreeMap::new();
    for line in text.lines().filter(|l| !l.trim_start().starts_with('#')) {
        if !line.starts_with(' ') && line.ends_with(':') {
            if !server.is_empty() {
                out.insert(
                    server.clone(),
                    (
                        vals["type"].parse().unwrap(),
                        vals["base"].parse().unwrap(),
                        vals["multiplier"].parse().unwrap(),
                    ),
                );
            }
            server = line.trim_end_matches(':').to_string();
            vals.clear();
        } else if let Some((k, v)) = line.split_once(':') {
            vals.insert(k.trim().into(), v.trim().into());
        }
    }
    out.insert(
        server,
        (
            vals["type"].parse().unwrap(),
            vals["base"].parse().unwrap(),
            vals["multiplier"].parse().unwrap(),
        ),
    );
    out
}

#[test]
fn map_and_masks_read_back() {
    let building = Building::single(demo_floor(&poinav_author::DemoBuilding {
        room2_door_width_m: 0.6,
        ..Default::default()
    }));
    let profile = RobotProfile::paper();
    let dir = tempfile::tempdir().unwrap();
    let summary = write_bundle(&building, &profile, &Nav2Options::default(), dir.path()).unwrap();
    let sub = dir.path().join("00-ground-floor");
    assert_eq!(summary.storeys[0].folder, "00-ground-floor");

    let map = load(&sub.join("map.yaml"));
    let y = read_yaml(&sub.join("map.yaml"));
    assert_eq!(y["mode"], "trinary");
    assert_eq!(
        (y["occupied_thresh"].as_str(), y["free_thresh"].as_str()),
        ("0.65", "0.196")
    );
    assert_eq!(map.origin[2], 0.0);
    assert_eq!(map.resolution, 0.05);
    // The whole map equals the grid, cell by cell.
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    let g = &nav.floors[0].grid.occupancy;
    assert_eq!((map.width, map.height), (g.width, g.height));
    assert_eq!(map.origin[..2], [g.origin.x, g.origin.y]);
    for i in 0..g.len() {
        let want = match g.cells[i] {
            CellState::Free => 0,
            CellState::Occupied => 100,
            CellState::Unknown => -1,
        };
        assert_eq!(map.data[i], want, "cell {i}");
    }
    // With Nav2's default free_thresh 0.25 the unknown grey 205 would load as free: p = 50 / 255
    // = 0.196 < 0.25. That is why the bundle writes 0.196.
    let yaml = std::fs::read_to_string(sub.join("map.yaml")).unwrap();
    std::fs::write(
        sub.join("map-0.25.yaml"),
        yaml.replace("free_thresh: 0.196", "free_thresh: 0.25"),
    )
    .unwrap();
    let default_thresh = load(&sub.join("map-0.25.yaml"));
    assert_eq!(default_thresh.at(-0.5, 5.0), 0);
    assert!(!default_thresh.data.contains(&-1));
    // In world coordinates: rooms free, walls occupied, outside unknown, the BLOCKED door shut.
    assert_eq!(map.at(2.0, 2.0), 0);
    assert_eq!(map.at(6.2, 5.4), 0);
    assert_eq!(map.at(1.0, 4.1), 100);
    assert_eq!(map.at(-0.5, 5.0), -1);
    assert_eq!(map.at(6.2, 4.1), 100);
    assert_eq!(map.at(2.0, 4.1), 0);

    let info = filter_info(&sub.join("costmap_filter_info.yaml"));
    let (kt, kb, km) = info["keepout_filter_info_server"];
    let (st, sb, sm) = info["speed_filter_info_server"];
    assert_eq!((kt, st), (0, 1));

    // Keepout: 100 on the BLOCKED door only.
    let keepout = load(&sub.join("keepout_mask.yaml"));
    assert_eq!(kb + km * f64::from(keepout.at(6.2, 4.1)), 100.0);
    assert_eq!(keepout.at(2.0, 4.1), 0);
    assert_eq!(keepout.at(2.0, 2.0), 0);
    let keep_cells = keepout.data.iter().filter(|v| **v == 100).count();
    // 0.60 x 0.20 m at 0.05 m.
    assert_eq!(keep_cells, 12 * 4);
    assert_eq!(keep_cells, summary.storeys[0].keepout_cells);

    // Speed: the C-1 corridor (SPEED_REDUCTION) at 50%, rooms without limit (mask 0).
    let speed = load(&sub.join("speed_mask.yaml"));
    assert_eq!(read_yaml(&sub.join("speed_mask.yaml"))["mode"], "scale");
    let corridor = speed.at(6.2, 5.4);
    assert_eq!(
        sb + sm * f64::from(corridor),
        100.0 * RoleSpeeds::default().speed_reduction
    );
    assert_eq!(speed.at(2.0, 2.0), 0);
    assert_eq!(speed.at(-0.5, 5.0), 0);
}

#[test]
fn speed_mask_for_narrow_doors_and_hazards() {
    let building = Building::single(office_floor());
    let profile = RobotProfile::paper();
    let dir = tempfile::tempdir().unwrap();
    let speeds = RoleSpeeds {
        hazard: 0.3,
        narrow: 0.4,
        speed_reduction: 0.6,
        ..Default::default()
    };
    let options = Nav2Options {
        nav: NavOptions {
            speeds,
            ..Default::default()
        },
        ..Default::default()
    };
    write_bundle(&building, &profile, &options, dir.path()).unwrap();
    let sub = dir.path().join("00-office-level");
    let speed = load(&sub.join("speed_mask.yaml"));
    let (_, base, mult) =
        filter_info(&sub.join("costmap_filter_info.yaml"))["speed_filter_info_server"];
    let limit = |x: f64, y: f64| base + mult * f64::from(speed.at(x, y));
    let floor = office_floor();
    let centre = |name: &str| {
        let z = floor.zone(name).unwrap();
        poinav_nav::polygon::interior_point(&z.ring).unwrap()
    };
    let c = centre("Office 10"); // B-1
    assert_eq!(limit(c.x, c.y), 30.0);
    let c = centre("Office 11");
    assert_eq!(speed.at(c.x, c.y), 0);
    let c = centre("Corridor A");
    assert_eq!(limit(c.x, c.y), 60.0);
    // Office 7's 0.80 m door (RESTRICTED, B-2).
    let d = floor
        .doors
        .iter()
        .find(|d| d.name.as_deref() == Some("Door Office 7"))
        .unwrap();
    assert_eq!(limit(d.center.x, d.center.y), 40.0);
    // Office 50's BLOCKED door is in the keepout mask.
    let keepout = load(&sub.join("keepout_mask.yaml"));
    let d = floor
        .doors
        .iter()
        .find(|d| d.name.as_deref() == Some("Door Office 50"))
        .unwrap();
    assert_eq!(keepout.at(d.center.x, d.center.y), 100);
}

fn graph_check(building: &Building, dir: &Path) -> (Value, BTreeMap<u64, Vec<u64>>) {
    let profile = RobotProfile::paper();
    let text = std::fs::read_to_string(dir.join("route_graph.geojson")).unwrap();
    let graph: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(graph["type"], "FeatureCollection");
    let features = graph["features"].as_array().unwrap();
    let mut ids = BTreeSet::new();
    let mut nodes = BTreeMap::new();
    let mut adj: BTreeMap<u64, Vec<u64>> = BTreeMap::new();
    let mut directed = BTreeSet::new();
    for f in features {
        let id = f["properties"]["id"].as_u64().unwrap();
        assert!(ids.insert(id), "id {id} twice");
        if f["geometry"]["type"] == "Point" {
            let c = &f["geometry"]["coordinates"];
            nodes.insert(
                id,
                DVec2::new(c[0].as_f64().unwrap(), c[1].as_f64().unwrap()),
            );
            assert_eq!(f["properties"]["frame"], "map");
        }
    }
    let nav = Navigator::new(building, &profile, &NavOptions::default()).unwrap();
    let grid = &nav.floors[0].grid;
    for f in features
        .iter()
        .filter(|f| f["geometry"]["type"] == "MultiLineString")
    {
        let p = &f["properties"];
        let (s, e) = (p["startid"].as_u64().unwrap(), p["endid"].as_u64().unwrap());
        let (a, b) = (nodes[&s], nodes[&e]);
        directed.insert((s, e));
        adj.entry(s).or_default().push(e);
        assert!(p["cost"].as_f64().unwrap() > 0.0);
        assert_eq!(p["overridable"], true);
        let speed = p["metadata"]["speed_limit"].as_f64().unwrap();
        assert!(speed > 0.0 && speed <= 100.0);
        assert!(
            p["metadata"]["speed_limit"].is_f64(),
            "speed_limit must be a float"
        );
        assert!(p["metadata"]["abs_speed_limit"].as_f64().unwrap() <= profile.max_speed_m_s);
        // The segment is collision-free for the robot's centre.
        let n = (a.distance(b) / 0.01).ceil() as usize + 1;
        for k in 0..=n {
            let q = a.lerp(b, k as f64 / n as f64);
            let cell = grid.occupancy.cell_of(q).unwrap();
            assert!(
                grid.traversable(cell),
                "edge {s}->{e} leaves free space at {q}"
            );
        }
    }
    for (s, e) in &directed {
        assert!(directed.contains(&(*e, *s)), "edge {s}->{e} has no reverse");
    }
    (graph, adj)
}

fn node_named(graph: &Value, name: &str) -> Option<u64> {
    graph["features"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["properties"]["metadata"]["name"] == name)
        .map(|f| f["properties"]["id"].as_u64().unwrap())
}

fn reachable(adj: &BTreeMap<u64, Vec<u64>>, from: u64) -> BTreeSet<u64> {
    let mut seen = BTreeSet::from([from]);
    let mut queue = VecDeque::from([from]);
    while let Some(n) = queue.pop_front() {
        for m in adj.get(&n).into_iter().flatten() {
            if seen.insert(*m) {
                queue.push_back(*m);
            }
        }
    }
    seen
}

#[test]
fn route_graph_is_a_valid_nav2_graph() {
    let building = Building::single(demo());
    let dir = tempfile::tempdir().unwrap();
    write_bundle(
        &building,
        &RobotProfile::paper(),
        &Nav2Options::default(),
        dir.path(),
    )
    .unwrap();
    let (graph, adj) = graph_check(&building, &dir.path().join("00-ground-floor"));
    let r1 = node_named(&graph, "Room 1").unwrap();
    let reach = reachable(&adj, r1);
    for k in 2..=6 {
        assert!(
            reach.contains(&node_named(&graph, &format!("Room {k}")).unwrap()),
            "Room {k}"
        );
    }
    // The RESTRICTED door's edges are slow (B-2), the corridor's at the C-1 speed.
    let d2 = node_named(&graph, "Door Room 2").unwrap();
    let slow = graph["features"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["properties"]["startid"] == d2)
        .all(|f| f["properties"]["metadata"]["speed_limit"].as_f64().unwrap() <= 50.0);
    assert!(slow);
    // Every edge into that door asks for it to be opened on entry, naming its GlobalId, and
    // is slowed by its B-2; the edges leaving it do not ask again.
    let door_id = building.floors[0]
        .doors
        .iter()
        .find(|d| d.name.as_deref() == Some("Door Room 2"))
        .unwrap()
        .id
        .clone();
    let edges: Vec<&Value> = graph["features"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["geometry"]["type"] == "MultiLineString")
        .map(|f| &f["properties"])
        .collect();
    let into: Vec<&&Value> = edges.iter().filter(|p| p["endid"] == d2).collect();
    assert!(into.len() >= 2, "{}", into.len());
    for p in &into {
        let op = &p["operations"][format!("OpenDoor {door_id}")];
        assert_eq!(op["type"], "OpenDoor", "{p}");
        assert_eq!(op["trigger"], "ON_ENTER");
        assert_eq!(op["metadata"]["door_id"], door_id.as_str());
        assert_eq!(
            op["metadata"]["service_name"],
            poinav_nav::route_graph::door_service(&door_id)
        );
        assert_eq!(p["metadata"]["speed_limit"], 50.0);
        assert!(p["metadata"]["speed_roles"]
            .as_array()
            .unwrap()
            .contains(&"B-2".into()));
    }
    for p in edges.iter().filter(|p| p["startid"] == d2) {
        assert!(p["operations"].is_null(), "{p}");
    }
    // README and topology.
    let readme = std::fs::read_to_string(dir.path().join("README.md")).unwrap();
    assert!(readme.contains("load_map") && readme.contains("route_graph.geojson"));
    let topo: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("topology.json")).unwrap())
            .unwrap();
    assert_eq!(topo["format"], "poinav-topology");
    // Deterministic output.
    let dir2 = tempfile::tempdir().unwrap();
    write_bundle(
        &building,
        &RobotProfile::paper(),
        &Nav2Options::default(),
        dir2.path(),
    )
    .unwrap();
    assert_eq!(
        std::fs::read(dir.path().join("route_graph.geojson")).unwrap(),
        std::fs::read(dir2.path().join("route_graph.geojson")).unwrap(),
        "the building's route graph"
    );
    for f in [
        "map.pgm",
        "map.yaml",
        "keepout_mask.pgm",
        "speed_mask.pgm",
        "route_graph.geojson",
    ] {
        assert_eq!(
            std::fs::read(dir.path().join("00-ground-floor").join(f)).unwrap(),
            std::fs::read(dir2.path().join("00-ground-floor").join(f)).unwrap(),
            "{f}"
        );
    }
}

#[test]
fn blocked_door_has_no_route_graph_edges() {
    let building = Building::single(demo_floor(&poinav_author::DemoBuilding {
        room2_door_width_m: 0.6,
        ..Default::default()
    }));
    let dir = tempfile::tempdir().unwrap();
    write_bundle(
        &building,
        &RobotProfile::paper(),
        &Nav2Options::default(),
        dir.path(),
    )
    .unwrap();
    let (graph, adj) = graph_check(&building, &dir.path().join("00-ground-floor"));
    assert!(node_named(&graph, "Door Room 2").is_none());
    let reach = reachable(&adj, node_named(&graph, "Room 1").unwrap());
    assert!(!reach.contains(&node_named(&graph, "Room 2").unwrap()));
    assert!(reach.contains(&node_named(&graph, "Room 3").unwrap()));
}

#[test]
fn office_route_graph() {
    let building = Building::single(office_floor());
    let dir = tempfile::tempdir().unwrap();
    let summary = write_bundle(
        &building,
        &RobotProfile::paper(),
        &Nav2Options::default(),
        dir.path(),
    )
    .unwrap();
    println!(
        "office route graph: {} nodes, {} edges",
        summary.storeys[0].graph_nodes, summary.storeys[0].graph_edges
    );
    let (graph, adj) = graph_check(&building, &dir.path().join("00-office-level"));
    let reach = reachable(&adj, node_named(&graph, "Entrance West").unwrap());
    assert!(reach.contains(&node_named(&graph, "Office 98").unwrap()));
    assert!(reach.contains(&node_named(&graph, "Entrance East").unwrap()));
    assert!(!reach.contains(&node_named(&graph, "Office 50").unwrap()));
}

#[test]
fn a_site_is_cropped_away_and_a_storey_with_nothing_to_navigate_is_skipped() {
    let profile = RobotProfile::paper();
    let ground = demo_floor(&poinav_author::DemoBuilding::default());
    let plain = tempfile::tempdir().unwrap();
    let alone = write_bundle(
        &Building::single(ground.clone()),
        &profile,
        &Nav2Options::default(),
        plain.path(),
    )
    .unwrap();
    let (w, h) = (alone.storeys[0].width, alone.storeys[0].height);

    // The same storey on a 200 x 120 m site slab, with a roof storey above holding only the
    // roof: the ground map is no bigger than the building alone plus the 1 m apron and margin.
    let site = |x0: f64, y0: f64, x1: f64, y1: f64, class: &str| poinav_nav::FloorObstacle {
        id: class.into(),
        class: class.into(),
        kind: poinav_nav::ObstacleKind::Structure,
        rings: vec![poinav_nav::polygon::rect(x0, y0, x1, y1)],
        roles: vec![],
    };
    let mut on_site = ground.clone();
    on_site
        .obstacles
        .push(site(-100.0, -60.0, 100.0, 60.0, "IfcSite"));
    let roof = poinav_nav::Floor {
        name: "Roof".into(),
        elevation_m: 3.0,
        obstacles: vec![site(-1.0, -1.0, 20.0, 12.0, "IfcRoof")],
        ..Default::default()
    };
    let building = Building {
        floors: vec![on_site, roof],
        connections: vec![],
        levels: vec![],
    };
    let dir = tempfile::tempdir().unwrap();
    let summary = write_bundle(&building, &profile, &Nav2Options::default(), dir.path()).unwrap();
    assert_eq!(summary.storeys.len(), 1);
    let (cw, ch) = (summary.storeys[0].width, summary.storeys[0].height);
    // 2 m more on each side at most (apron 1 m + margin 1 m), 0.05 m cells: 80 cells.
    assert!(cw <= w + 80 && ch <= h + 80, "{cw} x {ch} vs {w} x {h}");
    assert!(
        cw < 4000 / 2 && ch < 2400 / 2,
        "not the whole site: {cw} x {ch}"
    );
    assert_eq!(
        summary.skipped,
        [poinav_nav::nav2::SkippedStorey {
            floor: "Roof".into(),
            reason: "no spaces or doors (1 other element)".into()
        }]
    );
    assert!(!dir.path().join("01-roof").exists());
    let readme = std::fs::read_to_string(dir.path().join("README.md")).unwrap();
    assert!(
        readme.contains("- Roof: no spaces or doors (1 other element)"),
        "{readme}"
    );
}

#[test]
fn the_building_graph_joins_storeys_through_the_lift() {
    let building = two_storeys(true);
    let profile = RobotProfile::paper();
    let dir = tempfile::tempdir().unwrap();
    let summary = write_bundle(&building, &profile, &Nav2Options::default(), dir.path()).unwrap();
    let per_storey: usize = summary.storeys.iter().map(|s| s.graph_nodes).sum();
    let graph: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("route_graph.geojson")).unwrap(),
    )
    .unwrap();
    let features = graph["features"].as_array().unwrap();
    let nodes: BTreeMap<u64, &Value> = features
        .iter()
        .filter(|f| f["geometry"]["type"] == "Point")
        .map(|f| (f["properties"]["id"].as_u64().unwrap(), &f["properties"]))
        .collect();
    assert_eq!(nodes.len(), per_storey);
    assert_eq!(summary.building_graph.nodes, per_storey);
    let ids: BTreeSet<u64> = features
        .iter()
        .map(|f| f["properties"]["id"].as_u64().unwrap())
        .collect();
    assert_eq!(ids.len(), features.len(), "ids unique");
    // Each storey's nodes in its own frame.
    for p in nodes.values() {
        let frame = match p["metadata"]["storey"].as_str().unwrap() {
            "Ground floor" => "map_00_ground_floor",
            "First floor" => "map_01_first_floor",
            other => panic!("storey {other}"),
        };
        assert_eq!(p["frame"], frame);
    }
    // The lift joins the storeys both ways (the stairs are BLOCKED for wheels: no landing),
    // at its travel time: 30 s wait + 3.5 m at 1 m/s.
    let links: Vec<&Value> = features
        .iter()
        .filter(|f| f["geometry"]["type"] == "MultiLineString")
        .map(|f| &f["properties"])
        .filter(|p| p["metadata"]["connection"].is_string())
        .collect();
    assert_eq!(links.len(), 2);
    assert_eq!(summary.building_graph.storey_links, 2);
    for p in &links {
        assert_eq!(p["metadata"]["connection"], "lift");
        assert_eq!(p["metadata"]["element"], "lift-1");
        assert_eq!(p["cost"], 33.5);
        assert_eq!(p["overridable"], false);
        let (s, e) = (
            &nodes[&p["startid"].as_u64().unwrap()],
            &nodes[&p["endid"].as_u64().unwrap()],
        );
        assert_eq!(s["metadata"]["kind"], "landing");
        assert_eq!(e["metadata"]["kind"], "landing");
        assert_ne!(s["frame"], e["frame"]);
        assert_eq!(p["metadata"]["to_frame"], e["frame"]);
        let op = &p["operations"]["CallLift lift-1"];
        assert_eq!(op["type"], "CallLift");
        assert_eq!(op["trigger"], "ON_ENTER");
        assert_eq!(
            op["metadata"]["service_name"],
            "/poinav/lifts/llift_x2dx1/call"
        );
        assert_eq!(op["metadata"]["to_storey"], e["metadata"]["storey"]);
    }
    assert!(!nodes
        .values()
        .any(|p| p["metadata"]["element"] == "stair-1"));
    // The README documents the fields and the operations' plugins.
    let readme = std::fs::read_to_string(dir.path().join("README.md")).unwrap();
    for key in [
        "storey_index",
        "speed_roles",
        "nav2_route::TriggerEvent",
        "OpenDoor",
        "CallLift",
        "to_frame",
        "overridable: false",
        "map_00_ground_floor",
        "--z 3.5 --frame-id map --child-frame-id map_01_first_floor",
    ] {
        assert!(readme.contains(key), "{key}");
    }
}

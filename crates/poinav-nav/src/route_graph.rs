//! The nav2_route graphs of a Nav2 bundle, in the GeoJSON that nav2_route's
//! `GeoJsonGraphFileLoader` reads: one per storey (`<folder>/route_graph.geojson`, every node
//! in the frame [`Nav2Options::frame`]) and one for the whole building (`route_graph.geojson`
//! at the bundle's top, each node in its storey's frame `<frame>_<folder>` with `-` as `_`;
//! nav2_route moves nodes into its route frame through TF as it loads a graph, so the bundle's
//! README gives the static transforms to publish for those frames).
//!
//! Nodes are `Point` features, `properties`: `id`, `frame`, `metadata` with `kind` (`zone`,
//! `door`, `landing` or `waypoint`, a corner of a collision-free path), `storey` (name) and
//! `storey_index`, and for zones, doors and landings `element` (GlobalId), `name`, `roles`
//! (POI role labels); doors add `status`, `clear_width_m`, `doorless`; landings `connection`
//! (`stair`, `ramp`, `lift`), `status` and `to_floors`.
//!
//! Edges are `MultiLineString` features, every one in both directions, `properties`: `id`,
//! `startid`, `endid`, `cost`, `overridable`, `metadata` and, where there is something to do,
//! `operations` (an object of `{type, trigger, metadata}` by name, as the loader reads them).
//! Ids are unique across nodes and edges of a file.
//!
//! - On a storey, `cost` is the driving time in seconds at the role speeds:
//!   `cost = Σ ℓ_k / (v_max · f_k)`, the edge cut into pieces `ℓ_k` at most a quarter cell long
//!   and `f_k` the speed fraction ([`crate::speed::RoleSpeeds`]: the slower of the zone's and
//!   the door's roles) of the cell under each piece's middle, `v_max` the profile's top speed;
//!   on a uniform edge `length_m / abs_speed_limit`. `overridable: true`. `metadata`:
//!   `speed_limit` (percent of `v_max`, the slowest fraction along the edge; what nav2_route's
//!   `AdjustSpeedLimit` operation publishes when the edge is entered), `abs_speed_limit` (m/s),
//!   `length_m`, `speed_roles` (the roles that set the speeds along it: `B-1`, `B-2`,
//!   `C-1 SPEED_REDUCTION`, ...), `zones` and `doors` (GlobalIds crossed, in order along the
//!   edge) and `zone_names`, `door_names`.
//! - An edge crossing a door (not a doorless opening) carries the operation [`OPEN_DOOR`]
//!   (`trigger: ON_ENTER`, `metadata`: `door_id` = the door's GlobalId, `door_name`,
//!   `service_name` = [`door_service`]), for nav2_route's `TriggerEvent` plugin; not an edge
//!   that starts at that door's own node (the robot is already in the opened doorway).
//! - `AdjustSpeedLimit` is not listed in `operations`: nav2_route runs it on every edge change
//!   by itself (an ON_STATUS_CHANGE operation, in the server's default `operations`) and it
//!   reads `metadata.speed_limit` of the edge entered; listed as a graph operation the server
//!   would reject it ("does not exist in route operations loaded").
//! - In the building graph, edges joining storeys go from a landing to a landing of the same
//!   stair, ramp or lift: `cost` = the connection's travel time in seconds
//!   ([`crate::VerticalConnection::travel_time_s`], the same `poinav route` counts),
//!   `overridable: false` (distance scorers would make a lift free), `metadata`: `connection`
//!   (`stair`, `ramp`, `lift`), `element`, `name`, `status`, `from_storey`, `to_storey`,
//!   `to_frame`, `speed_limit` 100; a lift's edges carry the operation [`CALL_LIFT`]
//!   (`ON_ENTER`, `metadata`: `lift_id`, `from_storey`, `to_storey`, `service_name` =
//!   [`lift_service`]).
//!
//! Closed doors and connections (BLOCKED for the profile, or no room for the robot) have no
//! node and no edge. No value is `null` (the loader fails a whole graph on one): a member
//! without a value (an unnamed element's `name`) is left out. The same building and options
//! give the same bytes.

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec2;
use serde_json::{json, Map, Value};

use crate::graph::{round6, EdgeKind, NodeOf};
use crate::nav2::Nav2Options;
use crate::navigator::Navigator;
use crate::route::{astar_window, simplify, window_of, CellCost};

/// The operation name (`type`) of door edges: configure a nav2_route `TriggerEvent` plugin
/// under this name.
pub const OPEN_DOOR: &str = "OpenDoor";
/// The operation name (`type`) of lift edges between storeys (a `TriggerEvent` too).
pub const CALL_LIFT: &str = "CallLift";

/// A node of a route graph.
#[derive(Debug, Clone)]
pub struct GraphNode {
    /// Position, world metres.
    pub p: DVec2,
    /// The topology node it stands for (`None` for path corners).
    pub topology: Option<usize>,
    /// `metadata`.
    pub meta: Value,
}

/// A directed edge of a route graph.
#[derive(Debug, Clone)]
pub struct GraphEdge {
    /// Start node (index in the graph's nodes).
    pub start: usize,
    /// End node.
    pub end: usize,
    /// `cost`, seconds.
    pub cost_s: f64,
    /// `overridable`.
    pub overridable: bool,
    /// `metadata`.
    pub meta: Value,
    /// `operations` by name (empty: none).
    pub operations: Map<String, Value>,
}

/// The route graph of one storey.
#[derive(Debug, Clone)]
pub struct StoreyGraph {
    /// Storey index.
    pub floor: usize,
    /// Nodes.
    pub nodes: Vec<GraphNode>,
    /// Directed edges, both directions of each pair.
    pub edges: Vec<GraphEdge>,
    /// Topology node -> graph node, for the zones, doors and landings present.
    pub port: BTreeMap<usize, usize>,
}

/// A ROS 2 name token for a GlobalId: letters and digits kept, `_` written `_u` and any other
/// character `_x<hex>x`, so different ids give different names and no name has `__` or
/// starts with a digit (`first` is prefixed).
fn ros_token(first: char, id: &str) -> String {
    let mut s = String::from(first);
    for c in id.chars() {
        match c {
            'a'..='z' | 'A'..='Z' | '0'..='9' => s.push(c),
            '_' => s.push_str("_u"),
            '$' => s.push_str("_d"),
            other => {
                s.push_str("_x");
                s.push_str(&format!("{:x}", other as u32));
                s.push('x');
            }
        }
    }
    s
}

/// The service a door's [`OPEN_DOOR`] operation calls: `/poinav/doors/d<GlobalId>/open`, the
/// GlobalId's `_` written `_u` and `$` written `_d` (ROS 2 names allow neither `$` nor `__`).
pub fn door_service(global_id: &str) -> String {
    format!("/poinav/doors/{}/open", ros_token('d', global_id))
}

/// The service a lift's [`CALL_LIFT`] operation calls: `/poinav/lifts/l<GlobalId>/call`
/// (escaped as in [`door_service`]).
pub fn lift_service(global_id: &str) -> String {
    format!("/poinav/lifts/{}/call", ros_token('l', global_id))
}

/// The frame of storey folder `folder` in the building graph: `<frame>_<folder>`, `-` as `_`.
pub fn storey_frame(options: &Nav2Options, folder: &str) -> String {
    format!("{}_{}", options.frame, folder.replace('-', "_"))
}

/// What a straight segment crosses on a storey's grid.
struct Crossing {
    zones: Vec<usize>,
    doors: Vec<usize>,
    slowest: f64,
    time_s: f64,
}

fn crossing(nav: &Navigator<'_>, fi: usize, p: DVec2, q: DVec2) -> Crossing {
    let fnav = &nav.floors[fi];
    let g = &fnav.grid.occupancy;
    let base = 1.0 / nav.profile.max_speed_m_s;
    let len = p.distance(q);
    let n = ((len / (g.resolution_m / 4.0)).ceil() as usize).max(1);
    let (mut zones, mut doors) = (Vec::new(), Vec::new());
    let mut slowest: f64 = 1.0;
    for k in 0..=n {
        let Some(i) = g.cell_of(p.lerp(q, k as f64 / n as f64)) else {
            continue;
        };
        slowest = slowest.min(fnav.speed(i));
        if let Some(z) = g.zone[i]
            .map(|z| z.get())
            .filter(|z| zones.last() != Some(z))
        {
            zones.push(z);
        }
        if let Some(d) = g.door[i]
            .map(|d| d.get())
            .filter(|d| doors.last() != Some(d))
        {
            doors.push(d);
        }
    }
    let piece = len / n as f64;
    let time_s = (0..n)
        .map(|k| {
            let t = (k as f64 + 0.5) / n as f64;
            let f = g.cell_of(p.lerp(q, t)).map_or(1.0, |i| fnav.speed(i));
            piece * base / f
        })
        .sum();
    Crossing {
        zones,
        doors,
        slowest,
        time_s,
    }
}

fn zone_label(z: &crate::floor::FloorZone) -> String {
    z.name
        .clone()
        .or_else(|| z.long_name.clone())
        .unwrap_or_else(|| z.id.to_string())
}

fn roles(roles: &[poinav_roles::Role]) -> Value {
    json!(roles.iter().map(|r| r.label()).collect::<Vec<_>>())
}

/// The route graph of storey `fi`: its open zones, doors and landings, joined inside each zone
/// (each to its `options.neighbours` nearest others plus a spanning tree) and across open
/// boundaries by collision-free grid paths whose corners become waypoint nodes.
pub fn storey_graph(nav: &Navigator<'_>, fi: usize, options: &Nav2Options) -> StoreyGraph {
    let t = &nav.topology;
    let fnav = &nav.floors[fi];
    let grid = &fnav.grid;
    let g = &grid.occupancy;
    let floor = &nav.building.floors[fi];
    let costs = CellCost {
        floor: fnav,
        base: 1.0 / nav.profile.max_speed_m_s,
    };
    let mut nodes: Vec<GraphNode> = Vec::new();
    let mut edges: Vec<GraphEdge> = Vec::new();
    let mut made: BTreeSet<(usize, usize)> = BTreeSet::new();
    let mut waypoints: BTreeMap<usize, usize> = BTreeMap::new();
    // Topology node -> (graph node, cell).
    let mut port: Vec<Option<(usize, usize)>> = vec![None; t.nodes.len()];
    // Speed roles per zone and door.
    let zone_why: Vec<Vec<String>> = floor
        .zones
        .iter()
        .map(|z| nav.options.speeds.zone(z).1)
        .collect();
    let door_why: Vec<Vec<String>> = floor
        .doors
        .iter()
        .zip(&g.doors)
        .map(|(d, gd)| nav.options.speeds.door(d, gd.status).1)
        .collect();
    let zone_cells = nav.zone_cells(fi);
    for n in t.nodes.iter().filter(|n| n.floor == fi) {
        let cell = match n.of {
            NodeOf::Zone(z) => zone_cells.get(z.get()).copied().flatten(),
            NodeOf::Door(_) => {
                if !nav.open[n.id] {
                    continue;
                }
                grid.nearest_traversable(n.position(), 0.5)
            }
            NodeOf::Landing(_) => {
                if !nav.open[n.id] {
                    continue;
                }
                grid.nearest_traversable(n.position(), 1.0)
            }
        };
        let Some(cell) = cell else { continue };
        let mut meta = json!({
            "kind": n.kind(),
            "element": n.element,
            "name": n.name,
            "storey": floor.name,
            "storey_index": fi,
        });
        match n.of {
            NodeOf::Door(d) => {
                let d = &floor.doors[d.get()];
                meta["roles"] = roles(&d.roles);
                meta["status"] = json!(nav.status[n.id].0);
                meta["clear_width_m"] = json!(d.clear_width_m);
                meta["doorless"] = json!(d.doorless);
            }
            NodeOf::Landing(c) => {
                let c = &nav.building.connections[c];
                meta["roles"] = roles(&n.roles);
                meta["connection"] = json!(c.kind.label());
                meta["status"] = json!(nav.status[n.id].0);
                let others: Vec<&str> = c
                    .landings
                    .iter()
                    .filter(|l| l.floor != fi)
                    .filter_map(|l| nav.building.floors.get(l.floor).map(|f| f.name.as_str()))
                    .collect();
                meta["to_floors"] = json!(others);
            }
            NodeOf::Zone(z) => {
                meta["roles"] = roles(&floor.zones[z.get()].roles);
            }
        }
        port[n.id] = Some((nodes.len(), cell));
        nodes.push(GraphNode {
            p: g.center(cell),
            topology: Some(n.id),
            meta,
        });
    }
    // Pairs to join, per zone: its node and its doors and landings ("ports"), each to its
    // nearest `neighbours` others, plus a minimum spanning tree (by straight distance) so the
    // zone's part of the graph is connected; zones joined by open boundaries.
    let mut pairs: BTreeSet<(usize, usize)> = BTreeSet::new();
    for &zn in &t.zone_nodes[fi] {
        if port[zn].is_none() {
            continue;
        }
        let mut pts: Vec<usize> = vec![zn];
        pts.extend(
            t.adjacency[zn]
                .iter()
                .filter(|(e, v)| {
                    matches!(t.edges[*e].kind, EdgeKind::Door | EdgeKind::Landing)
                        && port[*v].is_some()
                })
                .map(|&(_, v)| v),
        );
        let pos = |n: usize| port[n].map_or(DVec2::ZERO, |x| nodes[x.0].p);
        for &p in &pts {
            let mut near: Vec<(f64, usize)> = pts
                .iter()
                .filter(|&&q| q != p)
                .map(|&q| (pos(q).distance(pos(p)), q))
                .collect();
            near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            for &(_, q) in near.iter().take(options.neighbours.max(1)) {
                pairs.insert((p.min(q), p.max(q)));
            }
        }
        // Prim's tree.
        let mut in_tree = vec![false; pts.len()];
        let mut best: Vec<(f64, usize)> = vec![(f64::INFINITY, 0); pts.len()];
        best[0] = (0.0, 0);
        for _ in 0..pts.len() {
            let Some(u) = (0..pts.len())
                .filter(|&i| !in_tree[i])
                .min_by(|&a, &b| best[a].0.total_cmp(&best[b].0).then(a.cmp(&b)))
            else {
                break;
            };
            in_tree[u] = true;
            if u != 0 {
                let (x, y) = (pts[u], pts[best[u].1]);
                pairs.insert((x.min(y), x.max(y)));
            }
            for v in 0..pts.len() {
                let d = pos(pts[u]).distance(pos(pts[v]));
                if !in_tree[v] && d < best[v].0 {
                    best[v] = (d, u);
                }
            }
        }
    }
    for e in t.edges.iter().filter(|e| e.kind == EdgeKind::Open) {
        if t.nodes[e.from].floor == fi && port[e.from].is_some() && port[e.to].is_some() {
            pairs.insert((e.from.min(e.to), e.from.max(e.to)));
        }
    }
    for (a, b) in pairs {
        let (Some((ga, ca)), Some((gb, cb))) = (port[a], port[b]) else {
            continue;
        };
        // Cells allowed: the zone both ends are in (or, for zones joined by an open
        // boundary, both zones) and the doors at the ends.
        let (za, zb) = (zones_of(nav, a, fi), zones_of(nav, b, fi));
        let shared: BTreeSet<usize> = za.intersection(&zb).copied().collect();
        let zones = if shared.is_empty() {
            za.union(&zb).copied().collect()
        } else {
            shared
        };
        let mut zones_ok = vec![false; floor.zones.len()];
        for z in zones {
            zones_ok[z] = true;
        }
        let mut doors_ok = vec![false; floor.doors.len()];
        for n in [a, b] {
            if let Some(d) = t.nodes[n].door() {
                doors_ok[d.get()] = true;
            }
        }
        // The end cells themselves too: a door's spot may fall just inside a neighbouring
        // zone.
        let allowed = |i: usize| {
            let z = g.zone[i];
            let d = g.door[i];
            i == ca
                || i == cb
                || (z.is_none_or(|z| zones_ok[z.get()]) && d.is_none_or(|d| doors_ok[d.get()]))
        };
        let cost = |i: usize| costs.cost(i);
        // Search only the box around the allowed zones and doors.
        let window = window_of(floor, g, &zones_ok, &doors_ok, &[ca, cb]);
        let Some(path) = astar_window(grid, window, ca, cb, allowed, cost, costs.base) else {
            continue;
        };
        let line = simplify(grid, &path, &allowed, &cost);
        // Corners become waypoint nodes (one per cell, shared by the paths through it).
        let mut ids = vec![ga];
        for p in &line[1..line.len().saturating_sub(1)] {
            let cell = g.cell_of(*p).unwrap_or(usize::MAX);
            let id = *waypoints.entry(cell).or_insert_with(|| {
                nodes.push(GraphNode {
                    p: *p,
                    topology: None,
                    meta: json!({"kind": "waypoint", "storey": floor.name, "storey_index": fi}),
                });
                nodes.len() - 1
            });
            ids.push(id);
        }
        ids.push(gb);
        ids.dedup();
        for w in ids.windows(2) {
            if made.contains(&(w[0], w[1])) {
                continue;
            }
            let (p, q) = (nodes[w[0]].p, nodes[w[1]].p);
            let c = crossing(nav, fi, p, q);
            for (s, e, forward) in [(w[0], w[1], true), (w[1], w[0], false)] {
                if !made.insert((s, e)) {
                    continue;
                }
                let (mut zs, mut ds) = (c.zones.clone(), c.doors.clone());
                if !forward {
                    zs.reverse();
                    ds.reverse();
                }
                edges.push(storey_edge(
                    nav, fi, &nodes, s, e, &c, zs, ds, &zone_why, &door_why,
                ));
            }
        }
    }
    StoreyGraph {
        floor: fi,
        nodes,
        edges,
        port: port
            .iter()
            .enumerate()
            .filter_map(|(n, p)| p.map(|(gn, _)| (n, gn)))
            .collect(),
    }
}

/// One directed edge on a storey from node `s` to `e`, crossing `zones` and `doors` in order.
#[allow(clippy::too_many_arguments)]
fn storey_edge(
    nav: &Navigator<'_>,
    fi: usize,
    nodes: &[GraphNode],
    s: usize,
    e: usize,
    c: &Crossing,
    zones: Vec<usize>,
    doors: Vec<usize>,
    zone_why: &[Vec<String>],
    door_why: &[Vec<String>],
) -> GraphEdge {
    let floor = &nav.building.floors[fi];
    let t = &nav.topology;
    let mut why: BTreeSet<&str> = BTreeSet::new();
    for &z in &zones {
        why.extend(zone_why[z].iter().map(String::as_str));
    }
    for &d in &doors {
        why.extend(door_why[d].iter().map(String::as_str));
    }
    // The door whose node the edge starts at, if any.
    let from_door = nodes[s]
        .topology
        .and_then(|n| t.nodes[n].door())
        .map(|d| d.get());
    let mut operations = Map::new();
    for &d in &doors {
        let door = &floor.doors[d];
        if door.doorless || from_door == Some(d) {
            continue;
        }
        operations.insert(
            format!("{OPEN_DOOR} {}", door.id),
            json!({
                "type": OPEN_DOOR,
                "trigger": "ON_ENTER",
                "metadata": {
                    "door_id": door.id,
                    "door_name": door.name,
                    "service_name": door_service(&door.id),
                },
            }),
        );
    }
    let len = nodes[s].p.distance(nodes[e].p);
    let meta = json!({
        "speed_limit": (c.slowest * 100.0).round(),
        "abs_speed_limit": round6(nav.profile.max_speed_m_s * c.slowest),
        "length_m": round6(len),
        "speed_roles": why,
        "zones": zones.iter().map(|&z| floor.zones[z].id.as_str()).collect::<Vec<_>>(),
        "zone_names": zones.iter().map(|&z| zone_label(&floor.zones[z])).collect::<Vec<_>>(),
        "doors": doors.iter().map(|&d| floor.doors[d].id.as_str()).collect::<Vec<_>>(),
        "door_names": doors
            .iter()
            .map(|&d| floor.doors[d].name.clone().unwrap_or_else(|| floor.doors[d].id.to_string()))
            .collect::<Vec<_>>(),
    });
    GraphEdge {
        start: s,
        end: e,
        cost_s: round6(c.time_s),
        overridable: true,
        meta,
        operations,
    }
}

/// The zones a topology node is in (a zone itself; a door's or landing's zones).
fn zones_of(nav: &Navigator<'_>, n: usize, fi: usize) -> BTreeSet<usize> {
    let t = &nav.topology;
    let node = &t.nodes[n];
    if let Some(z) = node.zone() {
        return [z.get()].into_iter().collect();
    }
    t.adjacency[n]
        .iter()
        .filter(|(_, v)| t.nodes[*v].floor == fi)
        .filter_map(|(_, v)| t.nodes[*v].zone())
        .map(|z| z.get())
        .collect()
}

/// `v` without its null members (an unnamed element's `name`): nav2_route's loader takes
/// numbers, booleans, strings, arrays and objects, and fails the whole graph on a null.
fn without_nulls(v: &Value) -> Value {
    match v {
        Value::Object(m) => Value::Object(
            m.iter()
                .filter(|(_, x)| !x.is_null())
                .map(|(k, x)| (k.clone(), without_nulls(x)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(
            a.iter()
                .filter(|x| !x.is_null())
                .map(without_nulls)
                .collect(),
        ),
        other => other.clone(),
    }
}

fn node_feature(id: usize, n: &GraphNode, frame: &str) -> Value {
    json!({
        "type": "Feature",
        "geometry": {"type": "Point", "coordinates": [round6(n.p.x), round6(n.p.y)]},
        "properties": {"id": id, "frame": frame, "metadata": without_nulls(&n.meta)},
    })
}

fn edge_feature(id: usize, start: usize, end: usize, p: DVec2, q: DVec2, e: &GraphEdge) -> Value {
    let mut props = json!({
        "id": id,
        "startid": start,
        "endid": end,
        "cost": e.cost_s,
        "overridable": e.overridable,
        "metadata": without_nulls(&e.meta),
    });
    if !e.operations.is_empty() {
        props["operations"] = without_nulls(&Value::Object(e.operations.clone()));
    }
    json!({
        "type": "Feature",
        "geometry": {"type": "MultiLineString", "coordinates": [[[round6(p.x), round6(p.y)], [round6(q.x), round6(q.y)]]]},
        "properties": props,
    })
}

/// The GeoJSON of one storey's graph: nodes `0..n` in `options.frame`, then its edges.
pub fn storey_geojson(nav: &Navigator<'_>, graph: &StoreyGraph, options: &Nav2Options) -> Value {
    let mut features: Vec<Value> = graph
        .nodes
        .iter()
        .enumerate()
        .map(|(id, n)| node_feature(id, n, &options.frame))
        .collect();
    let n = graph.nodes.len();
    for (k, e) in graph.edges.iter().enumerate() {
        let (p, q) = (graph.nodes[e.start].p, graph.nodes[e.end].p);
        features.push(edge_feature(n + k, e.start, e.end, p, q, e));
    }
    json!({
        "type": "FeatureCollection",
        "name": format!("{} ({})", nav.building.floors[graph.floor].name, nav.profile.name),
        "features": features,
    })
}

/// Counts of the building graph.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct BuildingGraphCounts {
    /// Nodes.
    pub nodes: usize,
    /// Directed edges, those joining storeys included.
    pub edges: usize,
    /// Directed edges joining storeys.
    pub storey_links: usize,
}

/// The GeoJSON of the whole building: every storey graph given (with its bundle folder) in its
/// storey's frame ([`storey_frame`]), node ids first (storey by storey), then the storeys'
/// edges, then the edges joining storeys through open stairs, ramps and lifts.
pub fn building_geojson(
    nav: &Navigator<'_>,
    graphs: &[(StoreyGraph, String)],
    options: &Nav2Options,
) -> (Value, BuildingGraphCounts) {
    let mut features = Vec::new();
    let counts = building_features(nav, graphs, options, &mut |f| {
        features.push(f);
        Ok::<(), std::convert::Infallible>(())
    })
    .unwrap_or_else(|e| match e {});
    (
        json!({
            "type": "FeatureCollection",
            "name": format!("building ({})", nav.profile.name),
            "features": features,
        }),
        counts,
    )
}

/// [`building_geojson`] written to `w` as pretty-printed JSON, the same bytes as
/// `serde_json::to_writer_pretty` of its value, one feature at a time: the whole building's
/// graph (52 MB of text for the 136 storeys of eight copies of the 17.9 MB synthetic file) is
/// never held as one value nor as one string.
pub fn write_building_geojson(
    nav: &Navigator<'_>,
    graphs: &[(StoreyGraph, String)],
    options: &Nav2Options,
    w: impl std::io::Write,
) -> Result<BuildingGraphCounts, serde_json::Error> {
    let doc = Streamed {
        nav,
        graphs,
        options,
        counts: std::cell::Cell::new(None),
    };
    serde_json::to_writer_pretty(w, &doc)?;
    Ok(doc.counts.get().unwrap_or(BuildingGraphCounts {
        nodes: 0,
        edges: 0,
        storey_links: 0,
    }))
}

/// The building's FeatureCollection, its features made as they are serialised.
struct Streamed<'s, 'a> {
    nav: &'s Navigator<'a>,
    graphs: &'s [(StoreyGraph, String)],
    options: &'s Nav2Options,
    counts: std::cell::Cell<Option<BuildingGraphCounts>>,
}

/// The `features` array of a [`Streamed`].
struct StreamedFeatures<'t, 's, 'a>(&'t Streamed<'s, 'a>);

impl serde::Serialize for Streamed<'_, '_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        // The keys in the order a `serde_json::Map` keeps them (sorted).
        let mut m = s.serialize_map(Some(3))?;
        m.serialize_entry("features", &StreamedFeatures(self))?;
        m.serialize_entry("name", &format!("building ({})", self.nav.profile.name))?;
        m.serialize_entry("type", "FeatureCollection")?;
        m.end()
    }
}

impl serde::Serialize for StreamedFeatures<'_, '_, '_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        let d = self.0;
        let mut seq = s.serialize_seq(None)?;
        let counts = building_features(d.nav, d.graphs, d.options, &mut |f| {
            seq.serialize_element(&f)
        })?;
        d.counts.set(Some(counts));
        seq.end()
    }
}

/// The features of [`building_geojson`], handed to `emit` in order: nodes, storey edges,
/// edges joining storeys.
fn building_features<E>(
    nav: &Navigator<'_>,
    graphs: &[(StoreyGraph, String)],
    options: &Nav2Options,
    emit: &mut impl FnMut(Value) -> Result<(), E>,
) -> Result<BuildingGraphCounts, E> {
    let t = &nav.topology;
    let mut offset = Vec::with_capacity(graphs.len());
    let mut by_floor: BTreeMap<usize, usize> = BTreeMap::new();
    let mut next = 0;
    for (k, (g, folder)) in graphs.iter().enumerate() {
        offset.push(next);
        by_floor.insert(g.floor, k);
        let frame = storey_frame(options, folder);
        for (i, n) in g.nodes.iter().enumerate() {
            let mut f = node_feature(next + i, n, &frame);
            f["properties"]["metadata"]["frame"] = json!(frame);
            emit(f)?;
        }
        next += g.nodes.len();
    }
    let n_nodes = next;
    for (k, (g, _)) in graphs.iter().enumerate() {
        for e in &g.edges {
            let (p, q) = (g.nodes[e.start].p, g.nodes[e.end].p);
            emit(edge_feature(
                next,
                offset[k] + e.start,
                offset[k] + e.end,
                p,
                q,
                e,
            ))?;
            next += 1;
        }
    }
    let mut links = 0;
    // Both directions of every connection edge whose landings are in the graph.
    let mut pairs: Vec<(usize, usize)> = t
        .edges
        .iter()
        .filter(|e| e.kind == EdgeKind::Connection)
        .flat_map(|e| [(e.from, e.to), (e.to, e.from)])
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    for (a, b) in pairs {
        let (na, nb) = (&t.nodes[a], &t.nodes[b]);
        let (Some(&ka), Some(&kb)) = (by_floor.get(&na.floor), by_floor.get(&nb.floor)) else {
            continue;
        };
        let (Some(&ga), Some(&gb)) = (graphs[ka].0.port.get(&a), graphs[kb].0.port.get(&b)) else {
            continue;
        };
        // Connection edges join landings.
        let NodeOf::Landing(ci) = na.of else {
            continue;
        };
        let c = &nav.building.connections[ci];
        let (from, to) = (
            &nav.building.floors[na.floor].name,
            &nav.building.floors[nb.floor].name,
        );
        let mut operations = Map::new();
        if c.kind == crate::ConnectionKind::Lift {
            operations.insert(
                format!("{CALL_LIFT} {}", c.id),
                json!({
                    "type": CALL_LIFT,
                    "trigger": "ON_ENTER",
                    "metadata": {
                        "lift_id": c.id,
                        "from_storey": from,
                        "to_storey": to,
                        "service_name": lift_service(&c.id),
                    },
                }),
            );
        }
        let edge = GraphEdge {
            start: ga,
            end: gb,
            cost_s: round6(nav.connection_cost(a, b) / nav.profile.max_speed_m_s),
            overridable: false,
            meta: json!({
                "connection": c.kind.label(),
                "element": c.id,
                "name": c.name,
                "status": nav.status[a].0,
                "from_storey": from,
                "to_storey": to,
                "to_frame": storey_frame(options, &graphs[kb].1),
                "speed_limit": 100.0,
            }),
            operations,
        };
        let (p, q) = (graphs[ka].0.nodes[ga].p, graphs[kb].0.nodes[gb].p);
        emit(edge_feature(
            next,
            offset[ka] + ga,
            offset[kb] + gb,
            p,
            q,
            &edge,
        ))?;
        next += 1;
        links += 1;
    }
    Ok(BuildingGraphCounts {
        nodes: n_nodes,
        edges: next - n_nodes,
        storey_links: links,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nulls_are_left_out_at_every_depth() {
        let v = json!({"name": null, "id": 3, "op": {"door_name": null, "x": [1, null]}});
        assert_eq!(without_nulls(&v), json!({"id": 3, "op": {"x": [1]}}));
    }

    #[test]
    fn service_names_are_ros_names_and_differ_per_id() {
        assert_eq!(
            door_service("2jTRqchjf7oB0yhQ6462T0"),
            "/poinav/doors/d2jTRqchjf7oB0yhQ6462T0/open"
        );
        assert_eq!(door_service("0a_$b"), "/poinav/doors/d0a_u_db/open");
        assert_eq!(lift_service("a__"), "/poinav/lifts/la_u_u/call");
        // `_` then `$` and the text `_d` differ.
        assert_ne!(door_service("a_$"), door_service("a_d"));
        for id in ["__", "_$", "$_", "a-b", "x"] {
            let s = door_service(id);
            assert!(!s.contains("__"), "{s}");
            assert!(
                s.chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '/'),
                "{s}"
            );
        }
    }
}

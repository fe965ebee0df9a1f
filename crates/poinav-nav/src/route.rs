//! Routes: the topology graph picks the zones, doors and vertical connections to use, then A*
//! on each storey's inflated grid (8-connected) finds the cells, with every
//! cell costing the time to cross it at the profile's speed slowed by its zone's and door's
//! roles (B-1, B-2, C-1 by protocol) and a penalty for closeness to obstacles. The cell path is
//! simplified by line of sight (never into a costlier straight line) and reported with its
//! length, expected time (travel at role speeds plus turning at the profile's rotation speed
//! plus vertical connections) and the doors it passes. An unreachable goal names the doors or
//! transitions that block it. A route may start or end `outside`: on the entrance apron in
//! front of the best open entrance.

use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::fmt;
use std::str::FromStr;

use glam::DVec2;
use poinav_roles::{AccessibilityStatus, Role};
use serde::Serialize;

use crate::graph::{round6, EdgeKind, NodeKind, NodeOf, Topology};
use crate::grid::{NavGrid, NEIGHBOURS};
use crate::navigator::{FloorNav, Navigator};
use crate::space_name::SpaceNames;
use crate::NavError;
use poinav_floor::ElementId;

/// Where a route starts or ends.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// A zone by Name, LongName or GlobalId: its most open spot.
    Zone(String),
    /// A point, world metres.
    Point(DVec2),
    /// Outside the building: in front of an open entrance (an exterior door, on its entrance
    /// apron), the one that gives the shortest way to the other end of the route.
    Outside,
}

/// A target on a storey (`None`: any storey for zones, the first for points).
#[derive(Debug, Clone, PartialEq)]
pub struct Place {
    /// Storey name.
    pub floor: Option<String>,
    /// What.
    pub target: Target,
}

impl Place {
    /// A zone on any storey.
    pub fn zone(name: &str) -> Place {
        Place {
            floor: None,
            target: Target::Zone(name.to_string()),
        }
    }

    /// A point on a storey.
    pub fn point(floor: Option<&str>, x: f64, y: f64) -> Place {
        Place {
            floor: floor.map(str::to_string),
            target: Target::Point(DVec2::new(x, y)),
        }
    }
}

/// A place's text names nothing (empty, or only `@Storey`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("`{0}` names no place")]
pub struct NoPlace(pub String);

impl FromStr for Place {
    type Err = NoPlace;

    /// `Room 1`, `Room 1@Level 2`, `3.5,2.0`, `3.5,2.0@Level 2`, `outside` or
    /// `outside@Level 1`.
    fn from_str(s: &str) -> Result<Place, NoPlace> {
        let (what, floor) = match s.rsplit_once('@') {
            Some((w, f)) => (w.trim(), Some(f.trim().to_string())),
            None => (s.trim(), None),
        };
        if what.is_empty() {
            return Err(NoPlace(s.to_string()));
        }
        let coords: Vec<Option<f64>> = what.split(',').map(|p| p.trim().parse().ok()).collect();
        let target = match coords.as_slice() {
            [Some(x), Some(y)] => Target::Point(DVec2::new(*x, *y)),
            _ if what.eq_ignore_ascii_case("outside") => Target::Outside,
            _ => Target::Zone(what.to_string()),
        };
        Ok(Place { floor, target })
    }
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.target {
            Target::Zone(z) => f.write_str(z)?,
            Target::Point(p) => write!(f, "({:.2}, {:.2})", p.x, p.y)?,
            Target::Outside => f.write_str("outside")?,
        }
        if let Some(fl) = &self.floor {
            write!(f, "@{fl}")?;
        }
        Ok(())
    }
}

/// A door or transition that blocks a route or makes a space unreachable.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Blocking {
    /// Storey name.
    pub floor: String,
    /// GlobalId.
    pub element: ElementId,
    /// Name.
    pub name: Option<String>,
    /// `door` or `landing` (stairs, ramps, lifts).
    pub kind: NodeKind,
    /// Status for the profile.
    pub status: AccessibilityStatus,
    /// Why it cannot be passed.
    pub reason: String,
}

impl Blocking {
    /// Name, else GlobalId.
    pub fn label(&self) -> &str {
        self.name.as_deref().unwrap_or(&self.element)
    }
}

impl fmt::Display for Blocking {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({})", self.label(), self.reason)
    }
}

/// Why there is no route.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Unreachable {
    /// Start.
    pub from: String,
    /// Goal.
    pub to: String,
    /// The doors and transitions on the least-blocked way between them.
    pub blocking: Vec<Blocking>,
    /// The message.
    pub message: String,
}

impl fmt::Display for Unreachable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// A door on a route.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassedDoor {
    /// Storey name.
    pub floor: String,
    /// GlobalId.
    pub id: ElementId,
    /// Name.
    pub name: Option<String>,
    /// Status for the profile.
    pub status: AccessibilityStatus,
    /// Clear width, metres.
    pub clear_width_m: f64,
    /// POI roles.
    pub roles: Vec<Role>,
    /// An opening without a door (a doorway).
    pub doorless: bool,
}

/// A vertical connection on a route.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassedConnection {
    /// GlobalId.
    pub id: ElementId,
    /// Name.
    pub name: Option<String>,
    /// `stair`, `ramp`, `lift`.
    pub kind: &'static str,
    /// From storey.
    pub from_floor: String,
    /// To storey.
    pub to_floor: String,
    /// Status for the profile.
    pub status: AccessibilityStatus,
    /// Time taken, seconds.
    pub time_s: f64,
}

/// The part of a route on one storey.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RouteLeg {
    /// Storey index.
    pub floor: usize,
    /// Storey name.
    pub floor_name: String,
    /// Simplified polyline, world metres.
    pub polyline: Vec<[f64; 2]>,
    /// Its length, metres.
    pub length_m: f64,
    /// Driving time at the role speeds, seconds.
    pub travel_time_s: f64,
    /// Turning time at the polyline's corners, seconds.
    pub turn_time_s: f64,
    /// Doors passed, in order.
    pub doors: Vec<PassedDoor>,
    /// Zones crossed, in order (names).
    pub zones: Vec<String>,
    /// Grid cells on the unsimplified path.
    #[serde(skip)]
    pub cells: Vec<usize>,
    /// Whether the topology graph guided the search (false when the search had to leave the
    /// graph's zones).
    pub guided: bool,
}

/// A route.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Route {
    /// Profile name.
    pub profile: String,
    /// Start.
    pub from: String,
    /// Goal.
    pub to: String,
    /// Per storey visited.
    pub legs: Vec<RouteLeg>,
    /// Vertical connections between the legs.
    pub connections: Vec<PassedConnection>,
    /// Total length on the storeys, metres.
    pub length_m: f64,
    /// Expected time, seconds: driving, turning and vertical connections.
    pub time_s: f64,
    /// Every door passed, in order.
    pub doors: Vec<PassedDoor>,
}

impl Route {
    /// As JSON.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or(serde_json::Value::Null)
    }
}

/// Cost and time per metre on a storey's cells.
pub(crate) struct CellCost<'a> {
    pub(crate) floor: &'a FloorNav,
    /// Seconds per metre at full speed.
    pub(crate) base: f64,
}

impl CellCost<'_> {
    /// Seconds per metre (time only).
    #[inline]
    pub(crate) fn time(&self, i: usize) -> f64 {
        self.base / self.floor.speed(i)
    }

    /// Planning cost per metre: time with the inflation penalty.
    #[inline]
    pub(crate) fn cost(&self, i: usize) -> f64 {
        self.time(i) * self.floor.grid.inflation_factor(i)
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct Open(f64, usize);

impl Eq for Open {}

impl Ord for Open {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .0
            .total_cmp(&self.0)
            .then_with(|| other.1.cmp(&self.1))
    }
}

impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// A* on `grid` from `start` to `goal` over traversable cells where `allowed` holds (8
/// neighbours), with `cost(i)` per metre on cell `i` (a step costs its length times the mean of
/// its two cells' costs) and `min_cost` a lower bound of `cost`. Returns the cell path.
pub fn astar(
    grid: &NavGrid,
    start: usize,
    goal: usize,
    allowed: impl Fn(usize) -> bool,
    cost: impl Fn(usize) -> f64,
    min_cost: f64,
) -> Option<Vec<usize>> {
    let g = &grid.occupancy;
    astar_window(
        grid,
        [0, 0, g.width, g.height],
        start,
        goal,
        allowed,
        cost,
        min_cost,
    )
}

/// [`astar`] inside the window `[col0, row0, col1, row1)` of the grid (its state is as large
/// as the window, so short searches in a large grid stay cheap).
pub fn astar_window(
    grid: &NavGrid,
    window: [usize; 4],
    start: usize,
    goal: usize,
    allowed: impl Fn(usize) -> bool,
    cost: impl Fn(usize) -> f64,
    min_cost: f64,
) -> Option<Vec<usize>> {
    let g = &grid.occupancy;
    let [c0, r0] = [window[0].min(g.width), window[1].min(g.height)];
    let [c1, r1] = [window[2].min(g.width), window[3].min(g.height)];
    if c1 <= c0 || r1 <= r0 {
        return None;
    }
    let (w, h) = ((c1 - c0) as i64, (r1 - r0) as i64);
    let res = g.resolution_m;
    // Local index <-> grid index.
    let global = |l: usize| (r0 + l / w as usize) * g.width + c0 + l % w as usize;
    let local = |i: usize| -> Option<usize> {
        let (c, r) = (i % g.width, i / g.width);
        (c >= c0 && c < c1 && r >= r0 && r < r1).then(|| (r - r0) * w as usize + (c - c0))
    };
    let ok = |i: usize| grid.traversable(i) && allowed(i);
    let (Some(ls), Some(lg)) = (local(start), local(goal)) else {
        return None;
    };
    if !ok(start) || !ok(goal) {
        return None;
    }
    let n = (w * h) as usize;
    let mut best = vec![f64::INFINITY; n];
    let mut parent = vec![u32::MAX; n];
    let mut closed = vec![false; n];
    let (gc, gr) = ((lg as i64) % w, (lg as i64) / w);
    let heuristic = |l: usize| {
        let (c, r) = ((l as i64) % w, (l as i64) / w);
        let (dx, dy) = ((c - gc).abs() as f64, (r - gr).abs() as f64);
        (dx.max(dy) + (std::f64::consts::SQRT_2 - 1.0) * dx.min(dy)) * res * min_cost
    };
    let mut heap = BinaryHeap::new();
    best[ls] = 0.0;
    heap.push(Open(heuristic(ls), ls));
    while let Some(Open(_, l)) = heap.pop() {
        if closed[l] {
            continue;
        }
        if l == lg {
            let mut path = vec![goal];
            let mut at = lg;
            while at != ls {
                at = parent[at] as usize;
                path.push(global(at));
            }
            path.reverse();
            return Some(path);
        }
        closed[l] = true;
        let (c, r) = ((l as i64) % w, (l as i64) / w);
        let ci = cost(global(l));
        for (dc, dr) in NEIGHBOURS {
            let (nc, nr) = (c + dc, r + dr);
            if nc < 0 || nr < 0 || nc >= w || nr >= h {
                continue;
            }
            let m = (nr * w + nc) as usize;
            let j = global(m);
            if closed[m] || !ok(j) {
                continue;
            }
            // Diagonal moves may pass the corner of a cell the robot's centre may not be on:
            // inflation already keeps the robot clear (as in Nav2's planners).
            let step = if dc != 0 && dr != 0 {
                std::f64::consts::SQRT_2 * res
            } else {
                res
            };
            let nd = best[l] + step * 0.5 * (ci + cost(j));
            if nd < best[m] {
                best[m] = nd;
                parent[m] = l as u32;
                heap.push(Open(nd + heuristic(m), m));
            }
        }
    }
    None
}

/// The window (see [`astar_window`]) around the allowed zones and doors of `floor` and the
/// cells `also`, two cells wider on every side.
pub(crate) fn window_of(
    floor: &crate::floor::Floor,
    g: &crate::grid::OccupancyGrid,
    zones_ok: &[bool],
    doors_ok: &[bool],
    also: &[usize],
) -> [usize; 4] {
    let mut lo = DVec2::splat(f64::MAX);
    let mut hi = DVec2::splat(f64::MIN);
    let zones = floor
        .zones
        .iter()
        .zip(zones_ok)
        .filter(|(_, ok)| **ok)
        .map(|(z, _)| &z.ring);
    let doors = floor
        .doors
        .iter()
        .zip(doors_ok)
        .filter(|(_, ok)| **ok)
        .map(|(d, _)| &d.ring);
    for p in zones.chain(doors).flatten() {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    for &c in also {
        lo = lo.min(g.center(c));
        hi = hi.max(g.center(c));
    }
    let col = |x: f64| ((x - g.origin.x) / g.resolution_m).floor().max(0.0) as usize;
    let row = |y: f64| ((y - g.origin.y) / g.resolution_m).floor().max(0.0) as usize;
    [
        col(lo.x).saturating_sub(2),
        row(lo.y).saturating_sub(2),
        col(hi.x) + 3,
        row(hi.y) + 3,
    ]
}

/// Samples along the segment `a`-`b` (at most a quarter cell apart), with the length each
/// stands for.
fn samples(grid: &NavGrid, a: DVec2, b: DVec2) -> impl Iterator<Item = (Option<usize>, f64)> + '_ {
    let len = a.distance(b);
    let n = ((len / (grid.occupancy.resolution_m / 4.0)).ceil() as usize).max(1);
    let piece = len / n as f64;
    (0..n).map(move |k| {
        let t = (k as f64 + 0.5) / n as f64;
        (grid.occupancy.cell_of(a.lerp(b, t)), piece)
    })
}

/// Line-of-sight simplification of a cell path: from each kept point, the farthest later cell
/// reachable by a straight segment over allowed cells that costs no more than the cell path
/// between them.
pub(crate) fn simplify(
    grid: &NavGrid,
    path: &[usize],
    allowed: &impl Fn(usize) -> bool,
    cost: &impl Fn(usize) -> f64,
) -> Vec<DVec2> {
    let g = &grid.occupancy;
    if path.len() < 2 {
        return path.iter().map(|&i| g.center(i)).collect();
    }
    // Cost of the cell path up to each index, integrated like the straight segments below.
    let mut prefix = vec![0.0; path.len()];
    for k in 1..path.len() {
        let (a, b) = (g.center(path[k - 1]), g.center(path[k]));
        let step: f64 = samples(grid, a, b)
            .map(|(cell, piece)| piece * cell.map_or(0.0, cost))
            .sum();
        prefix[k] = prefix[k - 1] + step;
    }
    let segment_cost = |a: DVec2, b: DVec2| -> Option<f64> {
        let mut total = 0.0;
        for (cell, piece) in samples(grid, a, b) {
            let i = cell?;
            if !grid.traversable(i) || !allowed(i) {
                return None;
            }
            total += piece * cost(i);
        }
        Some(total)
    };
    let mut out = vec![g.center(path[0])];
    let mut anchor = 0;
    while anchor + 1 < path.len() {
        let a = g.center(path[anchor]);
        let mut best = anchor + 1;
        let mut j = anchor + 2;
        while j < path.len() {
            match segment_cost(a, g.center(path[j])) {
                Some(c) if c <= (prefix[j] - prefix[anchor]) * (1.0 + 1e-3) + 1e-9 => best = j,
                _ => break,
            }
            j += 1;
        }
        out.push(g.center(path[best]));
        anchor = best;
    }
    out
}

/// Keeps in `best` (clearance, distance to `anchor`, cell) whichever of it and cell `i` is
/// farther from obstacles (ties, within a quarter cell: nearer to `anchor`; earlier cells win
/// exact ties): [`Navigator::zone_cell`]'s choice.
fn farther_or_nearer(
    best: &mut Option<(f32, f64, usize)>,
    grid: &NavGrid,
    i: usize,
    anchor: DVec2,
) {
    let g = &grid.occupancy;
    let tie = (g.resolution_m / 4.0) as f32;
    let c = grid.clearance_m[i].min(1e6);
    let d = g.center(i).distance(anchor);
    let better = match *best {
        None => true,
        Some((bc, bd, _)) => c > bc + tie || ((c - bc).abs() <= tie && d < bd),
    };
    if better {
        *best = Some((c, d, i));
    }
}

/// The polyline's length, driving time (seconds per metre from `time`) and turning time.
fn measure(
    grid: &NavGrid,
    line: &[DVec2],
    time: &impl Fn(usize) -> f64,
    rotation_deg_s: f64,
) -> (f64, f64, f64) {
    let mut length = 0.0;
    let mut travel = 0.0;
    for w in line.windows(2) {
        length += w[0].distance(w[1]);
        for (cell, piece) in samples(grid, w[0], w[1]) {
            travel += piece * cell.map_or(0.0, time);
        }
    }
    let mut turn_deg = 0.0;
    for w in line.windows(3) {
        let (u, v) = (w[1] - w[0], w[2] - w[1]);
        if u.length_squared() > 0.0 && v.length_squared() > 0.0 {
            turn_deg += u.angle_to(v).abs().to_degrees();
        }
    }
    (length, travel, turn_deg / rotation_deg_s.max(1e-9))
}

/// Nodes whose way from start to goal in the graph is at most this factor of the shortest
/// (plus [`NEAR_SLACK_M`]) open their zones and doors to a route's grid search.
pub const NEAR_FACTOR: f64 = 1.5;
/// See [`NEAR_FACTOR`], metres.
pub const NEAR_SLACK_M: f64 = 5.0;

/// A resolved place: storey, its topology node (zone or door) if any, and its cell.
#[derive(Debug, Clone, Copy)]
struct Spot {
    floor: usize,
    node: Option<usize>,
    cell: usize,
}

impl Navigator<'_> {
    fn floor_index(&self, name: Option<&str>) -> Result<Option<usize>, NavError> {
        match name {
            None => Ok(None),
            Some(n) => self.building.find_storey(n).map(Some),
        }
    }

    /// The cell a robot is sent to in a zone: the traversable cell farthest from obstacles
    /// (ties, within a quarter cell: nearest to the zone's interior point).
    pub fn zone_cell(&self, floor: usize, zone: usize) -> Option<usize> {
        let grid = &self.floors[floor].grid;
        let g = &grid.occupancy;
        let anchor = self.topology.nodes[self.topology.zone_nodes[floor][zone]].position();
        let mut best = None;
        for i in 0..g.len() {
            if g.zone[i].map(|z| z.get()) != Some(zone) || !grid.traversable(i) {
                continue;
            }
            farther_or_nearer(&mut best, grid, i, anchor);
        }
        best.map(|b| b.2)
    }

    /// [`Navigator::zone_cell`] of every zone of `floor` (index as in `Floor::zones`), in one
    /// pass over the grid instead of one per zone (the route graph asks for all of them).
    pub fn zone_cells(&self, floor: usize) -> Vec<Option<usize>> {
        let grid = &self.floors[floor].grid;
        let g = &grid.occupancy;
        let anchors: Vec<DVec2> = self.topology.zone_nodes[floor]
            .iter()
            .map(|&n| self.topology.nodes[n].position())
            .collect();
        let mut best = vec![None; anchors.len()];
        for i in 0..g.len() {
            let Some(z) = g.zone[i].map(|z| z.get()) else {
                continue;
            };
            if z >= anchors.len() || !grid.traversable(i) {
                continue;
            }
            farther_or_nearer(&mut best[z], grid, i, anchors[z]);
        }
        best.into_iter().map(|b| b.map(|b| b.2)).collect()
    }

    fn resolve(&self, place: &Place) -> Result<Spot, NavError> {
        let floor = self.floor_index(place.floor.as_deref())?;
        match &place.target {
            Target::Zone(name) => {
                let space = self
                    .building
                    .find_space(name, floor, place.floor.as_deref())?;
                let node = self.topology.zone_nodes[space.floor][space.zone.get()];
                let n = &self.topology.nodes[node];
                let cell = self.zone_cell(n.floor, space.zone.get()).ok_or_else(|| {
                    NavError::NoRoom(format!(
                        "space `{name}` has no spot where the robot fits (inflated by {:.3} m)",
                        self.floors[n.floor].grid.lethal_radius_m
                    ))
                })?;
                Ok(Spot {
                    floor: n.floor,
                    node: Some(node),
                    cell,
                })
            }
            Target::Outside => Err(NavError::Invalid(
                "outside is a place only at one end of a route".into(),
            )),
            Target::Point(p) => {
                let fi = floor.unwrap_or(0);
                let grid = &self
                    .floors
                    .get(fi)
                    .ok_or_else(|| NavError::NotFound("the building has no storey".into()))?
                    .grid;
                let cell = grid.nearest_traversable(*p, 1.0).ok_or_else(|| {
                    NavError::NoRoom(format!(
                        "no free spot for the robot within 1 m of ({:.2}, {:.2})",
                        p.x, p.y
                    ))
                })?;
                let g = &grid.occupancy;
                let node = match (g.zone[cell], g.door[cell]) {
                    (Some(z), _) => Some(self.topology.zone_nodes[fi][z.get()]),
                    (None, Some(d)) => self.topology.door(fi, d).map(|d| d.node),
                    (None, None) => None,
                };
                Ok(Spot {
                    floor: fi,
                    node,
                    cell,
                })
            }
        }
    }

    /// Seconds per metre at full speed.
    fn base_time(&self) -> f64 {
        1.0 / self.profile.max_speed_m_s
    }

    /// The cost in metres-equivalent of the connection edge between landings `a` and `b`.
    pub fn connection_cost(&self, a: usize, b: usize) -> f64 {
        let (na, nb) = (&self.topology.nodes[a], &self.topology.nodes[b]);
        // Connection edges join landings; anything else is no connection.
        let Some(c) = na.connection().map(|c| &self.building.connections[c]) else {
            return f64::INFINITY;
        };
        let dz =
            self.building.floors[na.floor].elevation_m - self.building.floors[nb.floor].elevation_m;
        c.travel_time_s(dz, &self.profile) * self.profile.max_speed_m_s
    }

    /// The doors and transitions blocking the way from `starts` to `goal`: the way through the
    /// fewest closed nodes, and those nodes on it (a stair, ramp or lift once, whatever the
    /// number of its landings on the way). Empty when no door or connection joins them at all.
    pub fn blocking(&self, starts: &[usize], goal: usize) -> Option<Vec<Blocking>> {
        const PENALTY: f64 = 1e7;
        let t = &self.topology;
        let (dist, prev) = t.search(
            starts,
            |n| Some(if self.open[n] { 0.0 } else { PENALTY }),
            |a, b| self.connection_cost(a, b),
        );
        if !dist[goal].is_finite() {
            return None;
        }
        let path = Topology::path_to(&prev, goal);
        // A stair, ramp or lift is one transition, named once (not once per landing).
        let mut seen: Vec<(NodeKind, &str)> = Vec::new();
        Some(
            path.iter()
                .filter(|&&n| !self.open[n])
                .filter(|&&n| {
                    let key = (t.nodes[n].kind(), t.nodes[n].element.as_str());
                    let new = !seen.contains(&key);
                    seen.push(key);
                    new
                })
                .map(|&n| {
                    let node = &t.nodes[n];
                    Blocking {
                        floor: self.building.floors[node.floor].name.clone(),
                        element: node.element.clone(),
                        name: node.name.clone(),
                        kind: node.kind(),
                        status: self.status[n].0,
                        reason: self.closed_reason(n),
                    }
                })
                .collect(),
        )
    }

    fn unreachable(
        &self,
        from: &Place,
        to: &Place,
        starts: &[usize],
        goal: Option<usize>,
    ) -> NavError {
        let blocking = goal.and_then(|g| self.blocking(starts, g));
        let message = match &blocking {
            Some(b) if !b.is_empty() => {
                let names: Vec<String> = b.iter().map(|x| x.to_string()).collect();
                format!(
                    "{to} is unreachable from {from} for {}: blocked by {}",
                    self.profile.name,
                    names.join(", ")
                )
            }
            Some(_) => format!(
                "{to} is unreachable from {from} for {}: no free path in the grid inflated by {:.3} m",
                self.profile.name, self.options.inflation.lethal_radius_m.unwrap_or(self.profile.width_m / 2.0)
            ),
            None => format!(
                "{to} is unreachable from {from}: no door, opening or vertical connection joins them"
            ),
        };
        NavError::Unreachable(Box::new(Unreachable {
            from: from.to_string(),
            to: to.to_string(),
            blocking: blocking.unwrap_or_default(),
            message,
        }))
    }

    /// Where a robot stands outside the building before entering by an open entrance on
    /// storey `floor` (any storey when `None`): on the entrance apron, in front of the entrance
    /// nearest through the graph to `other` (the route's other end).
    fn entrance_spot(&self, floor: Option<&str>, other: &Spot) -> Result<Spot, NavError> {
        let t = &self.topology;
        let apron = self.options.grid.entrance_apron_m;
        let exterior = self.exterior_doors(floor)?;
        let dist = other.node.map(|n| {
            t.search(
                &[n],
                |m| (self.open[m] || m == n).then_some(0.0),
                |x, y| self.connection_cost(x, y),
            )
            .0
        });
        let mut best: Option<(f64, Spot)> = None;
        let mut closed = Vec::new();
        for d in exterior {
            let grid = &self.floors[d.floor].grid;
            let frame = grid.occupancy.doors[d.door.get()].frame;
            let (Some(f), Some(side)) = (frame, d.outside_side()) else {
                continue;
            };
            if !self.open[d.node] {
                closed.push(format!(
                    "{} ({})",
                    t.nodes[d.node].label(),
                    self.closed_reason(d.node)
                ));
                continue;
            }
            let p = f.center + f.normal * side * (f.half_depth + apron / 2.0);
            let reach = apron / 2.0 + grid.occupancy.resolution_m;
            let Some(cell) = grid.nearest_traversable(p, reach) else {
                continue;
            };
            let score = match &dist {
                Some(dist) => dist[d.node] + t.nodes[d.node].position().distance(p),
                None if d.floor == other.floor => grid
                    .occupancy
                    .center(other.cell)
                    .distance(grid.occupancy.center(cell)),
                None => f64::INFINITY,
            };
            let spot = Spot {
                floor: d.floor,
                node: Some(d.node),
                cell,
            };
            if best.as_ref().is_none_or(|(b, _)| score < *b) {
                best = Some((score, spot));
            }
        }
        best.map(|(_, s)| s).ok_or_else(|| {
            NavError::NoRoom(if closed.is_empty() {
                "no entrance has room for the robot outside it".to_string()
            } else {
                format!(
                    "no entrance is open for {}: {}",
                    self.profile.name,
                    closed.join(", ")
                )
            })
        })
    }

    /// The exterior doors (entrances) of storey `floor` (any when `None`); an error when there
    /// is none.
    fn exterior_doors(
        &self,
        floor: Option<&str>,
    ) -> Result<Vec<&crate::graph::DoorSides>, NavError> {
        let floor = self.floor_index(floor)?;
        let exterior: Vec<&crate::graph::DoorSides> = self
            .topology
            .doors
            .iter()
            .filter(|d| d.exterior() && floor.is_none_or(|f| f == d.floor))
            .collect();
        if exterior.is_empty() {
            let spaces: usize = self.building.floors.iter().map(|f| f.zones.len()).sum();
            return Err(NavError::NoRoom(if spaces == 0 {
                "the building has no entrance: it has no spaces, so no door leads from a space to the outside".into()
            } else {
                "the building has no entrance (a door with a space on one side only)".into()
            }));
        }
        Ok(exterior)
    }

    /// A route from `from` to `to`.
    pub fn route(&self, from: &Place, to: &Place) -> Result<Route, NavError> {
        // A space named `outside` is that space.
        let named = |p: &Place| -> Result<Place, NavError> {
            if p.target == Target::Outside {
                let floor = self.floor_index(p.floor.as_deref())?;
                if self
                    .topology
                    .zone_node(self.building, "outside", floor)
                    .is_some()
                {
                    return Ok(Place {
                        floor: p.floor.clone(),
                        target: Target::Zone("outside".into()),
                    });
                }
                self.exterior_doors(p.floor.as_deref())?;
            }
            Ok(p.clone())
        };
        let (from, to) = (&named(from)?, &named(to)?);
        let (a, b) = match (&from.target, &to.target) {
            (Target::Outside, Target::Outside) => {
                return Err(NavError::Invalid(
                    "a route goes from outside into the building or out of it, not from outside to outside".into(),
                ))
            }
            (Target::Outside, _) => {
                let b = self.resolve(to)?;
                (self.entrance_spot(from.floor.as_deref(), &b)?, b)
            }
            (_, Target::Outside) => {
                let a = self.resolve(from)?;
                let b = self.entrance_spot(to.floor.as_deref(), &a)?;
                (a, b)
            }
            _ => (self.resolve(from)?, self.resolve(to)?),
        };
        let t = &self.topology;
        // The node sequence from the graph (start and goal nodes may be absent for points
        // outside every zone: then a single unguided leg).
        // Besides the graph's shortest node path, every node on a way nearly as short may be
        // used: the graph measures a zone from its interior point, a poor guide in large or
        // long zones, so the grid search gets the zones of all the plausible ways.
        let mut near = vec![false; t.nodes.len()];
        let nodes: Vec<usize> = match (a.node, b.node) {
            (Some(na), Some(nb)) => {
                let node_cost = |n: usize| (self.open[n] || n == na || n == nb).then_some(0.0);
                let connection = |x, y| self.connection_cost(x, y);
                let (dist, prev) = t.search(&[na], node_cost, connection);
                if !dist[nb].is_finite() {
                    return Err(self.unreachable(from, to, &[na], Some(nb)));
                }
                let (back, _) = t.search(&[nb], node_cost, connection);
                let bound = dist[nb] * NEAR_FACTOR + NEAR_SLACK_M;
                for (n, ok) in near.iter_mut().enumerate() {
                    *ok = dist[n] + back[n] <= bound;
                }
                Topology::path_to(&prev, nb)
            }
            _ if a.floor == b.floor => Vec::new(),
            _ => {
                return Err(NavError::Invalid(format!(
                    "{from} or {to} is in no space: routes between storeys start and end in spaces"
                )))
            }
        };
        // Split into storey legs at connection edges.
        let mut legs_nodes: Vec<Vec<usize>> = vec![Vec::new()];
        let mut connections = Vec::new();
        for w in nodes.windows(2) {
            let is_conn = t.adjacency[w[0]]
                .iter()
                .any(|&(e, v)| v == w[1] && t.edges[e].kind == EdgeKind::Connection);
            if legs_nodes.last().is_some_and(|l| l.is_empty()) {
                legs_nodes.last_mut().unwrap().push(w[0]);
            }
            if is_conn {
                legs_nodes.push(vec![w[1]]);
                connections.push((w[0], w[1]));
            } else {
                legs_nodes.last_mut().unwrap().push(w[1]);
            }
        }
        if nodes.len() == 1 {
            legs_nodes = vec![nodes.clone()];
        }
        let mut legs = Vec::new();
        let n_legs = legs_nodes.len();
        for (k, leg_nodes) in legs_nodes.iter().enumerate() {
            let floor = if leg_nodes.is_empty() {
                a.floor
            } else {
                t.nodes[leg_nodes[0]].floor
            };
            let landing_cell = |n: usize| {
                let node = &t.nodes[n];
                self.floors[floor]
                    .grid
                    .nearest_traversable(node.position(), 1.0)
                    .ok_or_else(|| {
                        NavError::Invalid(format!(
                            "the landing of {} on storey `{}` has no free spot for the robot within 1 m",
                            node.label(),
                            self.building.floors[floor].name
                        ))
                    })
            };
            let start = if k == 0 {
                a.cell
            } else {
                landing_cell(leg_nodes[0])?
            };
            let goal = if k + 1 == n_legs {
                b.cell
            } else {
                landing_cell(*leg_nodes.last().unwrap())?
            };
            let mut guide = leg_nodes.clone();
            guide.extend(
                (0..t.nodes.len())
                    .filter(|&n| near[n] && t.nodes[n].floor == floor && !leg_nodes.contains(&n)),
            );
            let leg = self.leg(floor, start, goal, &guide).ok_or_else(|| {
                self.unreachable(from, to, &a.node.into_iter().collect::<Vec<_>>(), b.node)
            })?;
            legs.push(leg);
        }
        let passed: Vec<PassedConnection> = connections
            .iter()
            .filter_map(|&(x, y)| {
                let (nx, ny) = (&t.nodes[x], &t.nodes[y]);
                let c = &self.building.connections[nx.connection()?];
                Some(PassedConnection {
                    id: c.id.clone(),
                    name: c.name.clone(),
                    kind: c.kind.label(),
                    from_floor: self.building.floors[nx.floor].name.clone(),
                    to_floor: self.building.floors[ny.floor].name.clone(),
                    status: self.status[x].0,
                    time_s: round6(self.connection_cost(x, y) / self.profile.max_speed_m_s),
                })
            })
            .collect();
        let length_m = legs.iter().map(|l| l.length_m).sum();
        let time_s = legs
            .iter()
            .map(|l| l.travel_time_s + l.turn_time_s)
            .sum::<f64>()
            + passed.iter().map(|c| c.time_s).sum::<f64>();
        Ok(Route {
            profile: self.profile.name.clone(),
            from: from.to_string(),
            to: to.to_string(),
            doors: legs.iter().flat_map(|l| l.doors.clone()).collect(),
            legs,
            connections: passed,
            length_m: round6(length_m),
            time_s: round6(time_s),
        })
    }

    /// One storey's leg from cell `start` to `goal`, guided by the graph nodes `guide` (zones
    /// and doors allowed); unguided over the whole storey when the guided search fails.
    fn leg(&self, floor: usize, start: usize, goal: usize, guide: &[usize]) -> Option<RouteLeg> {
        let fnav = &self.floors[floor];
        let grid = &fnav.grid;
        let g = &grid.occupancy;
        let t = &self.topology;
        let mut zones_ok = vec![false; self.building.floors[floor].zones.len()];
        let mut doors_ok = vec![false; self.building.floors[floor].doors.len()];
        for &n in guide {
            let node = &t.nodes[n];
            if node.floor != floor {
                continue;
            }
            match node.of {
                NodeOf::Zone(z) => zones_ok[z.get()] = true,
                NodeOf::Door(d) => doors_ok[d.get()] = true,
                NodeOf::Landing(_) => {}
            }
        }
        let costs = CellCost {
            floor: fnav,
            base: self.base_time(),
        };
        let cost = |i: usize| costs.cost(i);
        let min_cost = self.base_time();
        let guided_ok = |i: usize| {
            let z = g.zone[i];
            let d = g.door[i];
            z.is_none_or(|z| zones_ok[z.get()]) && d.is_none_or(|d| doors_ok[d.get()])
        };
        let everywhere = |_: usize| true;
        let (path, guided) = if guide.is_empty() {
            (astar(grid, start, goal, everywhere, cost, min_cost)?, false)
        } else if let Some(p) = astar_window(
            grid,
            window_of(
                &self.building.floors[floor],
                g,
                &zones_ok,
                &doors_ok,
                &[start, goal],
            ),
            start,
            goal,
            guided_ok,
            cost,
            min_cost,
        ) {
            (p, true)
        } else {
            (astar(grid, start, goal, everywhere, cost, min_cost)?, false)
        };
        let line = if guided {
            simplify(grid, &path, &guided_ok, &cost)
        } else {
            simplify(grid, &path, &everywhere, &cost)
        };
        let time = |i: usize| costs.time(i);
        let (length, travel, turn) = measure(grid, &line, &time, self.profile.rotation_speed_deg_s);
        let floor_model = &self.building.floors[floor];
        let mut doors = Vec::new();
        let mut zones: Vec<String> = Vec::new();
        let mut last_door = None;
        for &i in &path {
            let d = g.door[i];
            if let Some(k) = d.filter(|_| d != last_door).map(|d| d.get()) {
                let door = &floor_model.doors[k];
                doors.push(PassedDoor {
                    floor: floor_model.name.clone(),
                    id: door.id.clone(),
                    name: door.name.clone(),
                    status: g.doors[k].status,
                    clear_width_m: door.clear_width_m,
                    roles: door.roles.clone(),
                    doorless: door.doorless,
                });
            }
            last_door = d;
            if let Some(z) = g.zone[i] {
                let zone = &floor_model.zones[z.get()];
                let label = zone
                    .name
                    .clone()
                    .or_else(|| zone.long_name.clone())
                    .unwrap_or_else(|| zone.id.to_string());
                if zones.last() != Some(&label) {
                    zones.push(label);
                }
            }
        }
        Some(RouteLeg {
            floor,
            floor_name: floor_model.name.clone(),
            polyline: line.iter().map(|p| [round6(p.x), round6(p.y)]).collect(),
            length_m: round6(length),
            travel_time_s: round6(travel),
            turn_time_s: round6(turn),
            doors,
            zones,
            cells: path,
            guided,
        })
    }
}

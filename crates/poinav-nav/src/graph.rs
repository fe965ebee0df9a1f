//! The topology graph of a building: a node per space (zone), per door or opening and per
//! landing of a stair, ramp or lift; edges join each door to the zones on its two sides (the
//! spaces the model says the door bounds, `IfcRelSpaceBoundary` in IFC, placed on the sides
//! geometry finds them; without that, from geometry: which zone lies just beyond each face of
//! the door's passage) and each
//! landing to its zone and to the other landings of its connection. Statuses are the
//! profile's ([`Topology::statuses`]); the graph itself depends on geometry only.

use std::collections::{BTreeMap, BinaryHeap};

use glam::DVec2;
use poinav_roles::{AccessibilityStatus, RobotProfile, Role};
use serde::Serialize;

use crate::building::{passable, Building};
use crate::door_frame::DoorFrame;
use crate::door_status::door_status;
use crate::floor::Floor;
use crate::grid::NavGrid;
use crate::level::Entrance;
use crate::polygon;
use crate::zone_index::ZoneIndex;
use crate::{DoorIdx, ZoneIdx};
use poinav_floor::ElementId;

/// What a node stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum NodeKind {
    /// A space.
    Zone,
    /// A door or an opening.
    Door,
    /// Where a stair, ramp or lift is entered on one storey.
    Landing,
}

/// What a node stands for, with its index in its list; serialised as its `kind` and `index`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", content = "index", rename_all = "kebab-case")]
pub enum NodeOf {
    /// A space: its index in `Floor::zones`.
    Zone(ZoneIdx),
    /// A door or an opening: its index in `Floor::doors`.
    Door(DoorIdx),
    /// A landing of a stair, ramp or lift: the connection's index in
    /// `Building::connections`.
    Landing(usize),
}

impl NodeOf {
    /// Its kind.
    pub fn kind(self) -> NodeKind {
        match self {
            NodeOf::Zone(_) => NodeKind::Zone,
            NodeOf::Door(_) => NodeKind::Door,
            NodeOf::Landing(_) => NodeKind::Landing,
        }
    }
}

/// A node.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Node {
    /// Index in [`Topology::nodes`].
    pub id: usize,
    /// What it stands for: a zone, door or connection, with its index in its list.
    #[serde(flatten)]
    pub of: NodeOf,
    /// Storey index.
    pub floor: usize,
    /// GlobalId of the element.
    pub element: ElementId,
    /// Name (zone Name, else LongName; door name; connection name).
    pub name: Option<String>,
    /// Position: an interior point of the zone, the door's passage centre, the landing point.
    pub x: f64,
    /// See `x`.
    pub y: f64,
    /// POI roles of the element.
    pub roles: Vec<Role>,
}

impl Node {
    /// Its kind.
    pub fn kind(&self) -> NodeKind {
        self.of.kind()
    }

    /// The zone it stands for, if a zone node.
    pub fn zone(&self) -> Option<ZoneIdx> {
        match self.of {
            NodeOf::Zone(z) => Some(z),
            _ => None,
        }
    }

    /// The door it stands for, if a door node.
    pub fn door(&self) -> Option<DoorIdx> {
        match self.of {
            NodeOf::Door(d) => Some(d),
            _ => None,
        }
    }

    /// The connection (index in `Building::connections`) it is a landing of, if a landing.
    pub fn connection(&self) -> Option<usize> {
        match self.of {
            NodeOf::Landing(c) => Some(c),
            _ => None,
        }
    }

    /// Position.
    pub fn position(&self) -> DVec2 {
        DVec2::new(self.x, self.y)
    }

    /// The label used in reports: name, else GlobalId.
    pub fn label(&self) -> &str {
        self.name.as_deref().unwrap_or(&self.element)
    }
}

/// What an edge goes through.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum EdgeKind {
    /// Between a zone and one of its doors.
    Door,
    /// Between a zone and a landing in it.
    Landing,
    /// Between two landings of one stair, ramp or lift.
    Connection,
    /// Between two zones that touch without a wall or door between them (a virtual space
    /// boundary), found in an inflated grid where the robot's centre can cross it.
    Open,
}

/// An undirected edge.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Edge {
    /// Index in [`Topology::edges`].
    pub id: usize,
    /// One end (a zone for door and landing edges).
    pub from: usize,
    /// The other end.
    pub to: usize,
    /// Kind.
    pub kind: EdgeKind,
    /// Straight-line length between the ends, metres (0 for connections).
    pub length_m: f64,
}

/// One door and the zones on its two sides.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DoorSides {
    /// Storey index.
    pub floor: usize,
    /// Index in `Floor::doors`.
    pub door: DoorIdx,
    /// Its node.
    pub node: usize,
    /// Zone index on the side against the passage frame's normal and along it; `None` is
    /// outside the building (no zone within 0.5 m, or the door bounds one space only).
    pub zones: [Option<ZoneIdx>; 2],
    /// Where the sides come from: `true` from the spaces the door bounds
    /// ([`crate::FloorDoor::spaces`]), `false` from geometry alone.
    pub from_spaces: bool,
    /// An opening without a door ([`crate::FloorDoor::doorless`]). With a zone on one side
    /// only it is no entrance: it leads into what the model leaves undescribed (a lift shaft,
    /// a void, a room without an IfcSpace), not outside.
    pub doorless: bool,
    /// Its side without a zone is walled in (a closet or shaft without an IfcSpace, a
    /// courtyard), not outside: no entrance. Set by [`crate::Navigator`] from
    /// [`crate::grid::GridDoor::walled_in`].
    pub walled_in: bool,
    /// Its storey is not at ground level ([`Building::at_ground`]) and it does not open onto
    /// the terrain: its side without a zone is a balcony, a terrace, a light well or a drop,
    /// not the way in from outside: no entrance.
    pub off_ground: bool,
    /// Its side outside every space opens onto the terrain at its storey's walking level
    /// ([`crate::FloorDoor::terrain`]): on a storey not at ground level it is an entrance all
    /// the same ([`Entrance::Terrain`]).
    pub terrain: bool,
    /// Deciding its sides or rasterising it passed a bound ([`crate::bounds`]): its sides are
    /// not known ([`DoorSides::zones`] are both `None`, no edges), it is no entrance and not
    /// passable. Set by [`Topology::build_with`] and by [`crate::Navigator`] from
    /// [`crate::grid::GridDoor::gave_up`].
    pub gave_up: bool,
}

impl DoorSides {
    /// True for a door with a zone on one side only whose other side is outside: an entrance
    /// (never a doorway, nor a door into a walled-in room without a space).
    pub fn exterior(&self) -> bool {
        self.outside_side().is_some()
    }

    /// How an exterior door is reached from outside: from the terrain when its storey is not
    /// at ground level, else from the ground; `None` for other doors.
    pub fn entrance(&self) -> Option<Entrance> {
        self.exterior().then_some(if self.terrain {
            Entrance::Terrain
        } else {
            Entrance::Ground
        })
    }

    /// The side (-1 or +1 along the frame's normal) that leads outside, for an exterior door.
    pub fn outside_side(&self) -> Option<f64> {
        if self.doorless || self.walled_in || self.off_ground || self.gave_up {
            return None;
        }
        match self.zones {
            [None, Some(_)] => Some(-1.0),
            [Some(_), None] => Some(1.0),
            _ => None,
        }
    }
}

/// The building's topology.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Topology {
    /// Nodes: zones of every storey first, then doors, then landings.
    pub nodes: Vec<Node>,
    /// Edges.
    pub edges: Vec<Edge>,
    /// Per storey and zone index: the zone's node.
    pub zone_nodes: Vec<Vec<usize>>,
    /// Every door with its sides, storey by storey.
    pub doors: Vec<DoorSides>,
    /// Per connection: its landing nodes.
    pub landing_nodes: Vec<Vec<usize>>,
    /// Per node: (edge, other node).
    #[serde(skip)]
    pub adjacency: Vec<Vec<(usize, usize)>>,
}

/// How far beyond a door's faces zones are looked for, metres.
pub const SIDE_PROBE_M: f64 = 0.5;

/// The first zone (in floor order) containing `p`, among zones within
/// [`crate::bounds::ELEMENT_VERTICES`]: a fold over every zone, for a probe or two; many
/// probes of one floor go through its [`ZoneIndex`], which answers the same.
pub fn zone_at(floor: &Floor, p: DVec2) -> Option<ZoneIdx> {
    let found = floor.zones.iter().position(|z| {
        // A zone past the vertex bound is unknown in the grid, and doors near it are
        // undecided ([`crate::bounds::door_side_bounds`]): no search pays for its vertices.
        z.ring.len() <= crate::bounds::ELEMENT_VERTICES
            && polygon::bounds(&z.ring)
                .is_some_and(|(lo, hi)| p.x >= lo.x && p.y >= lo.y && p.x <= hi.x && p.y <= hi.y)
            && polygon::contains(&z.ring, p)
    });
    found.map(ZoneIdx::new)
}

/// The zone holding `p` ([`ZoneIndex::zone_at`]), else the nearest within [`SIDE_PROBE_M`]
/// (the first on a tie): where a landing or a robot standing at `p` is.
pub fn zone_near(floor: &Floor, zones: &ZoneIndex, p: DVec2) -> Option<ZoneIdx> {
    zones.zone_at(floor, p).or_else(|| {
        floor
            .zones
            .iter()
            .enumerate()
            .filter(|(_, z)| z.ring.len() <= crate::bounds::ELEMENT_VERTICES)
            .map(|(k, z)| (polygon::area_distance(&z.ring, p), k))
            .filter(|(d, _)| *d <= SIDE_PROBE_M)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, k)| ZoneIdx::new(k))
    })
}

/// The zones beyond the two faces of a passage frame (against and along its normal), probing
/// up to [`SIDE_PROBE_M`] out.
pub fn frame_zones(
    floor: &Floor,
    zones: &ZoneIndex,
    f: &crate::polygon::PassageFrame,
) -> [Option<ZoneIdx>; 2] {
    let step = 0.025;
    let mut sides = [None, None];
    for (s, side) in [-1.0, 1.0].into_iter().enumerate() {
        let mut k = 1;
        while sides[s].is_none() && (k as f64) * step <= SIDE_PROBE_M {
            let p = f.center + f.normal * side * (f.half_depth + k as f64 * step);
            sides[s] = zones.zone_at(floor, p);
            k += 1;
        }
    }
    sides
}

/// The zones on the two sides of a door (see [`DoorSides::zones`]): from the spaces the door
/// bounds ([`crate::FloorDoor::spaces`]) where given and present on the floor, each on the
/// side where geometry finds it or else nearer to it; a side the spaces leave empty (a
/// one-sided boundary, as many exporters write) takes the zone geometry finds beyond that
/// face, so only a door with no space behind it has a side outside; otherwise from geometry
/// alone (the zones just beyond the passage's faces).
pub fn door_zones(floor: &Floor, door: usize) -> [Option<ZoneIdx>; 2] {
    door_zones_in(floor, &ZoneIndex::new(floor), door)
}

/// [`door_zones`] with `floor`'s [`ZoneIndex`] (for many doors, build it once).
pub fn door_zones_in(floor: &Floor, zones: &ZoneIndex, door: usize) -> [Option<ZoneIdx>; 2] {
    let geometric = geometric_door_zones_in(floor, zones, door);
    let d = &floor.doors[door];
    let Some(ids) = d.spaces.as_ref().filter(|s| !s.is_empty()) else {
        return geometric;
    };
    // The door's own spaces on this floor (a space may have several regions).
    let own: Vec<ZoneIdx> = (0..floor.zones.len())
        .filter(|&z| ids.contains(&floor.zones[z].id))
        .map(ZoneIdx::new)
        .collect();
    if own.is_empty() {
        return geometric;
    }
    let frame = floor.door_frame_in(door, zones);
    let probe = |side: f64| match frame {
        Some(f) => f.center + f.normal * side * (f.half_depth + 0.25),
        None => d.center,
    };
    let mut sides = [None, None];
    for s in 0..2 {
        if let Some(z) = geometric[s].filter(|z| own.contains(z)) {
            sides[s] = Some(z);
        }
    }
    if sides[0].is_some() && sides[1].is_some() && sides[0] == sides[1] {
        sides[1] = None;
    }
    // As many sides as the door has spaces (at most two), the missing ones filled with the
    // nearest unused space.
    let distinct = {
        let mut v: Vec<&str> = own
            .iter()
            .map(|&z| floor.zones[z.get()].id.as_str())
            .collect();
        v.sort_unstable();
        v.dedup();
        v.len().min(2)
    };
    while sides.iter().flatten().count() < distinct {
        let used: Vec<&str> = sides
            .iter()
            .flatten()
            .map(|&z| floor.zones[z.get()].id.as_str())
            .collect();
        let mut best: Option<(f64, usize, ZoneIdx)> = None;
        for (s, side) in [(0, -1.0), (1, 1.0)] {
            if sides[s].is_some() {
                continue;
            }
            for &z in &own {
                if used.contains(&floor.zones[z.get()].id.as_str()) {
                    continue;
                }
                let dist = polygon::area_distance(&floor.zones[z.get()].ring, probe(side));
                if best.is_none_or(|(bd, _, _)| dist < bd) {
                    best = Some((dist, s, z));
                }
            }
        }
        let Some((_, s, z)) = best else {
            break;
        };
        sides[s] = Some(z);
    }
    // A side still empty: another space geometry finds beyond that face (never the space on
    // the other side again).
    for s in 0..2 {
        let other = sides[1 - s].map(|z| floor.zones[z.get()].id.as_str());
        if sides[s].is_none() {
            sides[s] = geometric[s].filter(|&z| Some(floor.zones[z.get()].id.as_str()) != other);
        }
    }
    sides
}

/// The zones on the two sides of a door from geometry alone.
pub fn geometric_door_zones(floor: &Floor, door: usize) -> [Option<ZoneIdx>; 2] {
    geometric_door_zones_in(floor, &ZoneIndex::new(floor), door)
}

/// [`geometric_door_zones`] with `floor`'s [`ZoneIndex`].
pub fn geometric_door_zones_in(
    floor: &Floor,
    zones: &ZoneIndex,
    door: usize,
) -> [Option<ZoneIdx>; 2] {
    let d = &floor.doors[door];
    let Some(f) = floor.door_frame_in(door, zones) else {
        // No passage ring: the two zones nearest to the centre within the probe distance.
        let mut near: Vec<(f64, usize)> = floor
            .zones
            .iter()
            .enumerate()
            .filter(|(_, z)| z.ring.len() <= crate::bounds::ELEMENT_VERTICES)
            .map(|(k, z)| (polygon::area_distance(&z.ring, d.center), k))
            .filter(|(dist, _)| *dist <= SIDE_PROBE_M)
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        return [
            near.first().map(|n| ZoneIdx::new(n.1)),
            near.get(1).map(|n| ZoneIdx::new(n.1)),
        ];
    };
    frame_zones(floor, zones, &f)
}

impl Topology {
    /// Builds the topology of `building` from its geometry, within the default bounds.
    pub fn build(building: &Building) -> Topology {
        Topology::build_with(building, &crate::bounds::StageBounds::default())
    }

    /// Builds the topology of `building` from its geometry; a door whose side search would
    /// pass `bounds` ([`crate::bounds::door_side_bounds`]) joins no zone and is marked
    /// [`DoorSides::gave_up`].
    pub fn build_with(building: &Building, bounds: &crate::bounds::StageBounds) -> Topology {
        let mut nodes = Vec::new();
        let mut zone_nodes = Vec::new();
        for (fi, floor) in building.floors.iter().enumerate() {
            let mut ids = Vec::new();
            for (k, z) in floor.zones.iter().enumerate() {
                let p = polygon::interior_point(&z.ring).unwrap_or(DVec2::ZERO);
                ids.push(nodes.len());
                nodes.push(Node {
                    id: nodes.len(),
                    of: NodeOf::Zone(ZoneIdx::new(k)),
                    floor: fi,
                    element: z.id.clone(),
                    name: z.name.clone().or_else(|| z.long_name.clone()),
                    x: p.x,
                    y: p.y,
                    roles: z.roles.clone(),
                });
            }
            zone_nodes.push(ids);
        }
        let mut edges = Vec::new();
        let mut doors = Vec::new();
        let indexes: Vec<ZoneIndex> = building.floors.iter().map(ZoneIndex::new).collect();
        for (fi, floor) in building.floors.iter().enumerate() {
            let zones = &indexes[fi];
            let undecided = crate::bounds::door_side_bounds(floor, bounds);
            for (k, d) in floor.doors.iter().enumerate() {
                let gave_up = undecided[k].is_some();
                let p = if gave_up {
                    d.frame().map_or(d.center, |f| f.center)
                } else {
                    floor.door_frame_in(k, zones).map_or(d.center, |f| f.center)
                };
                let node = nodes.len();
                nodes.push(Node {
                    id: node,
                    of: NodeOf::Door(DoorIdx::new(k)),
                    floor: fi,
                    element: d.id.clone(),
                    name: d.name.clone(),
                    x: p.x,
                    y: p.y,
                    roles: d.roles.clone(),
                });
                let zones = if gave_up {
                    [None, None]
                } else {
                    door_zones_in(floor, zones, k)
                };
                let mut linked: Vec<ZoneIdx> = zones.iter().flatten().copied().collect();
                linked.dedup();
                for z in linked {
                    let zn = zone_nodes[fi][z.get()];
                    edges.push(Edge {
                        id: edges.len(),
                        from: zn,
                        to: node,
                        kind: EdgeKind::Door,
                        length_m: nodes[zn].position().distance(p),
                    });
                }
                let from_spaces = d
                    .spaces
                    .as_ref()
                    .is_some_and(|ids| floor.zones.iter().any(|z| ids.contains(&z.id)));
                doors.push(DoorSides {
                    floor: fi,
                    door: DoorIdx::new(k),
                    node,
                    zones,
                    from_spaces,
                    doorless: floor.doors[k].doorless,
                    walled_in: false,
                    off_ground: !building.at_ground(fi) && !floor.doors[k].terrain,
                    terrain: !building.at_ground(fi) && floor.doors[k].terrain,
                    gave_up,
                });
            }
        }
        let mut landing_nodes = Vec::new();
        for (ci, c) in building.connections.iter().enumerate() {
            let mut ids = Vec::new();
            for l in &c.landings {
                let Some(floor) = building.floors.get(l.floor) else {
                    continue;
                };
                let node = nodes.len();
                nodes.push(Node {
                    id: node,
                    of: NodeOf::Landing(ci),
                    floor: l.floor,
                    element: c.id.clone(),
                    name: c.name.clone(),
                    x: l.point.x,
                    y: l.point.y,
                    roles: Vec::new(),
                });
                let zone = zone_near(floor, &indexes[l.floor], l.point);
                if let Some(z) = zone {
                    let zn = zone_nodes[l.floor][z.get()];
                    edges.push(Edge {
                        id: edges.len(),
                        from: zn,
                        to: node,
                        kind: EdgeKind::Landing,
                        length_m: nodes[zn].position().distance(l.point),
                    });
                }
                ids.push(node);
            }
            for w in ids.windows(2) {
                edges.push(Edge {
                    id: edges.len(),
                    from: w[0],
                    to: w[1],
                    kind: EdgeKind::Connection,
                    length_m: 0.0,
                });
            }
            landing_nodes.push(ids);
        }
        let mut adjacency = vec![Vec::new(); nodes.len()];
        for e in &edges {
            adjacency[e.from].push((e.id, e.to));
            adjacency[e.to].push((e.id, e.from));
        }
        Topology {
            nodes,
            edges,
            zone_nodes,
            doors,
            landing_nodes,
            adjacency,
        }
    }

    /// Adds an [`EdgeKind::Open`] edge between every two zones of storey `floor` whose
    /// traversable cells touch (4-neighbours, neither in a door) in `grid` along at least
    /// `min_cells` cell pairs.
    pub fn add_open_boundaries(&mut self, floor: usize, grid: &NavGrid, min_cells: usize) {
        let g = &grid.occupancy;
        let mut pairs: BTreeMap<(usize, usize), usize> = BTreeMap::new();
        let ok = |i: usize| g.zone[i].is_some() && g.door[i].is_none() && grid.traversable(i);
        for r in 0..g.height {
            for c in 0..g.width {
                let i = r * g.width + c;
                if !ok(i) {
                    continue;
                }
                let mut check = |j: usize| {
                    if ok(j) && g.zone[j] != g.zone[i] {
                        if let (Some(zi), Some(zj)) = (g.zone[i], g.zone[j]) {
                            let (a, b) = (zi.min(zj).get(), zi.max(zj).get());
                            *pairs.entry((a, b)).or_default() += 1;
                        }
                    }
                };
                if c + 1 < g.width {
                    check(i + 1);
                }
                if r + 1 < g.height {
                    check(i + g.width);
                }
            }
        }
        for ((a, b), count) in pairs {
            if count < min_cells.max(1) {
                continue;
            }
            let (na, nb) = (self.zone_nodes[floor][a], self.zone_nodes[floor][b]);
            let id = self.edges.len();
            self.edges.push(Edge {
                id,
                from: na,
                to: nb,
                kind: EdgeKind::Open,
                length_m: self.nodes[na]
                    .position()
                    .distance(self.nodes[nb].position()),
            });
            self.adjacency[na].push((id, nb));
            self.adjacency[nb].push((id, na));
        }
    }

    /// The door entry of storey `floor`'s door `door`.
    pub fn door(&self, floor: usize, door: DoorIdx) -> Option<&DoorSides> {
        self.doors
            .iter()
            .find(|d| d.floor == floor && d.door == door)
    }

    /// The node of a zone named `name` (Name or LongName) on storey `floor` (any storey when
    /// `None`; the first match).
    pub fn zone_node(
        &self,
        building: &Building,
        name: &str,
        floor: Option<usize>,
    ) -> Option<usize> {
        for (fi, f) in building.floors.iter().enumerate() {
            if floor.is_some_and(|x| x != fi) {
                continue;
            }
            if let Some(k) = f.zones.iter().position(|z| {
                z.name.as_deref() == Some(name)
                    || z.long_name.as_deref() == Some(name)
                    || z.id == name
            }) {
                return Some(self.zone_nodes[fi][k]);
            }
        }
        None
    }

    /// The status (and reason) of every door and landing node for `profile`; zones are
    /// always passable (FULL_ACCESS).
    pub fn statuses(
        &self,
        building: &Building,
        profile: &RobotProfile,
    ) -> Vec<(AccessibilityStatus, String)> {
        self.nodes
            .iter()
            .map(|n| match n.of {
                NodeOf::Zone(_) => (AccessibilityStatus::FullAccess, String::new()),
                NodeOf::Door(d) => door_status(&building.floors[n.floor].doors[d.get()], profile),
                NodeOf::Landing(c) => building.connections[c].status(profile),
            })
            .collect()
    }

    /// Entrances: the nodes of exterior doors.
    pub fn entrances(&self) -> Vec<usize> {
        self.doors
            .iter()
            .filter(|d| d.exterior())
            .map(|d| d.node)
            .collect()
    }

    /// Shortest paths from `starts`: edges cost their length (connections
    /// `connection_cost(a, b)`), entering a node costs `node_cost(node)`, and `None` there
    /// closes the node. Returns per node the distance and the previous node (`None` for
    /// starts and unreached nodes).
    pub fn search(
        &self,
        starts: &[usize],
        node_cost: impl Fn(usize) -> Option<f64>,
        connection_cost: impl Fn(usize, usize) -> f64,
    ) -> (Vec<f64>, Vec<Option<usize>>) {
        let n = self.nodes.len();
        let mut dist = vec![f64::INFINITY; n];
        let mut prev = vec![None; n];
        let mut heap = BinaryHeap::new();
        for &s in starts {
            if s < n && dist[s] > 0.0 {
                dist[s] = 0.0;
                heap.push(HeapItem(0.0, s));
            }
        }
        while let Some(HeapItem(d, u)) = heap.pop() {
            if d > dist[u] {
                continue;
            }
            for &(e, v) in &self.adjacency[u] {
                let Some(extra) = node_cost(v) else {
                    continue;
                };
                let w = match self.edges[e].kind {
                    EdgeKind::Connection => connection_cost(u, v),
                    _ => self.edges[e].length_m,
                };
                let nd = d + w + extra;
                if nd < dist[v] {
                    dist[v] = nd;
                    prev[v] = Some(u);
                    heap.push(HeapItem(nd, v));
                }
            }
        }
        (dist, prev)
    }

    /// The doors on the shortest way from zone `from` to zone `to` of storey `floor`, in
    /// order, through doors `usable` accepts only (and no stair, ramp or lift):
    /// [`Topology::search`] from `from`'s node. Empty when `from == to`; `None` when `to`
    /// cannot be reached.
    pub fn door_path(
        &self,
        floor: usize,
        from: ZoneIdx,
        to: ZoneIdx,
        usable: impl Fn(DoorIdx) -> bool,
    ) -> Option<Vec<DoorIdx>> {
        let start = *self.zone_nodes.get(floor)?.get(from.get())?;
        let goal = *self.zone_nodes[floor].get(to.get())?;
        let (dist, prev) = self.search(
            &[start],
            |n| {
                let node = &self.nodes[n];
                match node.of {
                    NodeOf::Zone(_) => Some(0.0),
                    NodeOf::Door(d) => (node.floor == floor && usable(d)).then_some(0.0),
                    NodeOf::Landing(_) => None,
                }
            },
            |_, _| f64::INFINITY,
        );
        if !dist[goal].is_finite() {
            return None;
        }
        Some(
            Topology::path_to(&prev, goal)
                .into_iter()
                .filter_map(|n| self.nodes[n].door())
                .collect(),
        )
    }

    /// The node path ending at `goal` from [`Topology::search`]'s `prev`.
    pub fn path_to(prev: &[Option<usize>], goal: usize) -> Vec<usize> {
        let mut path = vec![goal];
        let mut at = goal;
        while let Some(p) = prev[at] {
            at = p;
            path.push(at);
            if path.len() > prev.len() {
                break;
            }
        }
        path.reverse();
        path
    }

    /// The graph as JSON for `profile`: storeys, nodes, and edges carrying the door's or
    /// connection's clear width, status, reason and roles.
    pub fn to_json(&self, building: &Building, profile: &RobotProfile) -> serde_json::Value {
        let statuses = self.statuses(building, profile);
        let floors: Vec<serde_json::Value> = building
            .floors
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let mut v =
                    serde_json::json!({"index": i, "name": f.name, "elevation_m": f.elevation_m});
                if let Some(l) = building.levels.get(i) {
                    v["storey_elevation_m"] = serde_json::json!(l.storey_elevation_m);
                    v["level_from"] = serde_json::json!(l.from);
                    v["at_ground"] = serde_json::json!(l.at_ground);
                }
                v
            })
            .collect();
        let nodes: Vec<serde_json::Value> = self
            .nodes
            .iter()
            .map(|n| {
                let mut v = serde_json::json!({
                    "id": n.id,
                    "kind": n.kind(),
                    "floor": n.floor,
                    "element": n.element,
                    "name": n.name,
                    "x": round6(n.x),
                    "y": round6(n.y),
                    "roles": n.roles,
                });
                match n.of {
                    NodeOf::Door(d) => {
                        let sides = self.door(n.floor, d);
                        v["exterior"] = serde_json::json!(sides.is_some_and(|s| s.exterior()));
                        v["entrance"] = serde_json::json!(sides.and_then(|s| s.entrance()));
                        v["sides_from"] =
                            serde_json::json!(if sides.is_some_and(|s| s.from_spaces) {
                                "space-boundaries"
                            } else {
                                "geometry"
                            });
                        v["doorless"] = serde_json::json!(sides.is_some_and(|s| s.doorless));
                        v["status"] = serde_json::json!(statuses[n.id].0);
                        v["reason"] = serde_json::json!(statuses[n.id].1);
                    }
                    NodeOf::Landing(c) => {
                        let c = &building.connections[c];
                        v["connection"] = serde_json::json!(c.kind.label());
                        v["status"] = serde_json::json!(statuses[n.id].0);
                        v["reason"] = serde_json::json!(statuses[n.id].1);
                    }
                    NodeOf::Zone(z) => {
                        let z = &building.floors[n.floor].zones[z.get()];
                        v["long_name"] = serde_json::json!(z.long_name);
                        if let Some((sep, protocol)) = z.coordination {
                            v["coordination"] = serde_json::json!({
                                "min_separation_m": sep,
                                "protocol": protocol,
                            });
                        }
                    }
                }
                v
            })
            .collect();
        let edges: Vec<serde_json::Value> = self
            .edges
            .iter()
            .map(|e| {
                let through = &self.nodes[e.to];
                let mut v = serde_json::json!({
                    "id": e.id,
                    "from": e.from,
                    "to": e.to,
                    "kind": e.kind,
                    "length_m": round6(e.length_m),
                });
                match through.of {
                    NodeOf::Door(d) => {
                        let d = &building.floors[through.floor].doors[d.get()];
                        v["via"] = serde_json::json!(d.id);
                        v["name"] = serde_json::json!(d.name);
                        v["clear_width_m"] = serde_json::json!(d.clear_width_m);
                        v["required_width_m"] = serde_json::json!(profile.min_clearance_width());
                        v["status"] = serde_json::json!(statuses[through.id].0);
                        v["reason"] = serde_json::json!(statuses[through.id].1);
                        v["roles"] = serde_json::json!(d.roles);
                    }
                    NodeOf::Landing(c) => {
                        let c = &building.connections[c];
                        v["via"] = serde_json::json!(c.id);
                        v["name"] = serde_json::json!(c.name);
                        v["connection"] = serde_json::json!(c.kind.label());
                        v["clear_width_m"] = serde_json::json!(c.clear_width_m);
                        v["required_width_m"] = serde_json::json!(profile.min_clearance_width());
                        v["status"] = serde_json::json!(statuses[through.id].0);
                        v["reason"] = serde_json::json!(statuses[through.id].1);
                    }
                    NodeOf::Zone(_) => {}
                }
                v
            })
            .collect();
        serde_json::json!({
            "format": "poinav-topology",
            "version": 1,
            "profile": {
                "name": profile.name,
                "width_m": profile.width_m,
                "min_clearance_width_m": profile.min_clearance_width(),
            },
            "floors": floors,
            "nodes": nodes,
            "edges": edges,
        })
    }

    /// Nodes passable for `profile` (zones always; doors and landings by status, PENDING by
    /// `pending_passable`).
    pub fn open_nodes(
        &self,
        building: &Building,
        profile: &RobotProfile,
        pending_passable: bool,
    ) -> Vec<bool> {
        self.statuses(building, profile)
            .iter()
            .map(|(s, _)| passable(*s, pending_passable))
            .collect()
    }

    /// Zone names per storey, for messages: `Room 2` or its GlobalId.
    pub fn zone_labels(&self) -> BTreeMap<usize, String> {
        self.nodes
            .iter()
            .filter(|n| n.kind() == NodeKind::Zone)
            .map(|n| (n.id, n.label().to_string()))
            .collect()
    }
}

/// Rounds to micrometres for stable JSON.
pub fn round6(v: f64) -> f64 {
    (v * 1e6).round() / 1e6
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct HeapItem(f64, usize);

impl Eq for HeapItem {}

impl Ord for HeapItem {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        other
            .0
            .total_cmp(&self.0)
            .then_with(|| other.1.cmp(&self.1))
    }
}

impl PartialOrd for HeapItem {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

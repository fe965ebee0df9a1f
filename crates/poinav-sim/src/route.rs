//! Routes on the floor's zone/door graph: which zones each door joins, each door's axis, and the
//! shortest path (Dijkstra over door centres) from a point to a target zone as waypoints that
//! line the robot up with every door it passes. A stand-in until poinav-nav's routes land.

use glam::DVec2;
use poinav_nav::Floor;
use poinav_roles::AccessibilityStatus;

use crate::geometry::{point_in_ring, ring_centroid, ring_distance};

/// How far (metres) a door centre may lie from a zone's outline to join it.
const JOIN_M: f64 = 0.5;

/// A door as navigation sees it.
#[derive(Debug, Clone, PartialEq)]
pub struct NavDoor {
    /// Centre.
    pub center: DVec2,
    /// Unit normal of the wall the door is in (sign arbitrary); `None` for a degenerate ring.
    pub axis: Option<DVec2>,
    /// Clear width, metres.
    pub width: f64,
    /// Zones it joins, ascending.
    pub zones: Vec<u32>,
    /// False when BLOCKED.
    pub passable: bool,
}

/// The zone/door graph of a floor.
#[derive(Debug, Clone)]
pub struct NavGraph {
    /// Doors, in floor order.
    pub doors: Vec<NavDoor>,
    /// Zone outlines.
    pub zones: Vec<Vec<DVec2>>,
    /// A point inside each zone used as its goal (centroid, or the first vertex mean inside).
    pub goals: Vec<DVec2>,
}

/// The axis of a door ring: the normal of its longest edge.
fn door_axis(ring: &[DVec2]) -> Option<DVec2> {
    let n = ring.len();
    let mut best = (0.0, DVec2::ZERO);
    for i in 0..n {
        let e = ring[(i + 1) % n] - ring[i];
        let l = e.length();
        if l > best.0 + 1e-9 {
            best = (l, e / l);
        }
    }
    (best.0 > 0.0).then(|| best.1.perp())
}

impl NavGraph {
    /// The graph of `floor`.
    pub fn new(floor: &Floor) -> NavGraph {
        let zones: Vec<Vec<DVec2>> = floor.zones.iter().map(|z| z.ring.clone()).collect();
        let goals = zones
            .iter()
            .map(|r| {
                let c = ring_centroid(r);
                if point_in_ring(c, r) || r.is_empty() {
                    c
                } else {
                    // A point just inside the longest edge's middle.
                    let n = r.len();
                    (0..n)
                        .map(|i| {
                            let (a, b) = (r[i], r[(i + 1) % n]);
                            let m = (a + b) * 0.5 + (b - a).normalize_or_zero().perp() * 0.3;
                            ((b - a).length(), m)
                        })
                        .filter(|(_, m)| point_in_ring(*m, r))
                        .fold((0.0, c), |acc, x| if x.0 > acc.0 { x } else { acc })
                        .1
                }
            })
            .collect();
        let doors = floor
            .doors
            .iter()
            .map(|d| {
                let mut near: Vec<(f64, u32)> = zones
                    .iter()
                    .enumerate()
                    .map(|(i, r)| (ring_distance(d.center, r), i as u32))
                    .filter(|(dist, _)| *dist <= JOIN_M)
                    .collect();
                near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                near.truncate(2);
                let mut zones: Vec<u32> = near.iter().map(|x| x.1).collect();
                zones.sort_unstable();
                NavDoor {
                    center: d.center,
                    axis: door_axis(&d.ring),
                    width: d.clear_width_m,
                    zones,
                    passable: d.status != AccessibilityStatus::Blocked,
                }
            })
            .collect();
        NavGraph {
            doors,
            zones,
            goals,
        }
    }

    /// The zone containing `p` (first in floor order), else the nearest within 0.5 m.
    pub fn zone_at(&self, p: DVec2) -> Option<u32> {
        if let Some(i) = self.zones.iter().position(|r| point_in_ring(p, r)) {
            return Some(i as u32);
        }
        self.zones
            .iter()
            .enumerate()
            .map(|(i, r)| (ring_distance(p, r), i))
            .filter(|(d, _)| *d <= JOIN_M)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, i)| i as u32)
    }

    /// Doors on the shortest path from `from` to zone `to`, in order, for a robot `width` wide.
    pub fn door_path(&self, from: DVec2, to: u32, width: f64) -> Option<Vec<u32>> {
        let start = self.zone_at(from)?;
        if start == to {
            return Some(Vec::new());
        }
        let goal = self.goals[to as usize];
        let usable = |d: &NavDoor| d.passable && d.width >= width && d.zones.len() == 2;
        let n = self.doors.len();
        let mut dist = vec![f64::INFINITY; n];
        let mut prev: Vec<Option<usize>> = vec![None; n];
        let mut done = vec![false; n];
        for (i, d) in self.doors.iter().enumerate() {
            if usable(d) && d.zones.contains(&start) {
                dist[i] = from.distance(d.center);
            }
        }
        let mut best: Option<(f64, usize)> = None;
        while let Some(u) = (0..n)
            .filter(|&i| !done[i] && dist[i].is_finite())
            .min_by(|&a, &b| dist[a].total_cmp(&dist[b]).then(a.cmp(&b)))
        {
            done[u] = true;
            if self.doors[u].zones.contains(&to) {
                let total = dist[u] + self.doors[u].center.distance(goal);
                if best.is_none_or(|(b, _)| total < b) {
                    best = Some((total, u));
                }
            }
            for v in 0..n {
                if done[v] || !usable(&self.doors[v]) {
                    continue;
                }
                let shared = self.doors[u]
                    .zones
                    .iter()
                    .any(|z| self.doors[v].zones.contains(z));
                if !shared {
                    continue;
                }
                let nd = dist[u] + self.doors[u].center.distance(self.doors[v].center);
                if nd < dist[v] {
                    dist[v] = nd;
                    prev[v] = Some(u);
                }
            }
        }
        let (_, mut u) = best?;
        let mut path = vec![u as u32];
        while let Some(p) = prev[u] {
            path.push(p as u32);
            u = p;
        }
        path.reverse();
        Some(path)
    }

    /// Waypoints from `from` through `doors` to zone `to`'s goal: before and after every door
    /// a point `lead` metres out on its axis, so the robot crosses it straight; with each, the
    /// clear width of the door it passes through (its centre and exit), `None` elsewhere.
    pub fn waypoints(
        &self,
        from: DVec2,
        doors: &[u32],
        to: u32,
        lead: f64,
    ) -> (Vec<DVec2>, Vec<Option<f64>>) {
        let mut out = Vec::new();
        let mut widths = Vec::new();
        let mut prev = from;
        for &d in doors {
            let door = &self.doors[d as usize];
            match door.axis {
                Some(axis) => {
                    let n = if (door.center - prev).dot(axis) >= 0.0 {
                        axis
                    } else {
                        -axis
                    };
                    out.extend([door.center - n * lead, door.center, door.center + n * lead]);
                    widths.extend([None, Some(door.width), Some(door.width)]);
                }
                None => {
                    out.push(door.center);
                    widths.push(Some(door.width));
                }
            }
            prev = door.center;
        }
        out.push(self.goals[to as usize]);
        widths.push(None);
        (out, widths)
    }
}

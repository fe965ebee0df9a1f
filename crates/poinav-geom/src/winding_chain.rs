//! The boundary of a sum of oriented polygons in the plane: a multiset of directed edges in
//! which an edge and its reverse cancel, and its closed loops.
//!
//! The winding number of a sum of polygons at a point is the winding number of the sum's
//! boundary, and an edge shared by two polygons that run along it in opposite directions
//! (neighbouring triangles of a mesh facing the same way) adds nothing to it. So the region
//! a set of triangles covers with a non-zero count can be filled from the few edges left
//! after cancelling (a silhouette, a cut), not from every triangle: a polygon boolean on those
//! costs what the outline costs, not what the mesh costs.
//!
//! Points are merged on a grid of [`QUANTUM_M`] so that the same vertex reached through
//! different triangles cancels even when its coordinates differ in the last bits. Every
//! polygon added is closed, and cancelling removes an edge together with its reverse, so at
//! every point as many edges leave as arrive: the edges always split into closed loops.

use glam::DVec2;
use rustc_hash::FxHashMap;

/// The grid points are merged on, metres (0.1 µm, as fine as `i_overlay`'s own snapping for
/// a building).
pub const QUANTUM_M: f64 = 1e-7;

/// Directed edges with opposite ones cancelled.
#[derive(Debug, Default)]
pub struct WindingChain {
    ids: FxHashMap<[i64; 2], u32>,
    points: Vec<DVec2>,
    /// Per edge `(lo, hi)` of point ids (`lo < hi`): how many times it runs `lo -> hi`
    /// (negative: `hi -> lo`). Edges that cancelled out are removed.
    edges: FxHashMap<(u32, u32), i32>,
}

impl WindingChain {
    /// An empty chain.
    pub fn new() -> WindingChain {
        WindingChain::default()
    }

    fn id(&mut self, p: DVec2) -> u32 {
        let key = [
            (p.x / QUANTUM_M).round() as i64,
            (p.y / QUANTUM_M).round() as i64,
        ];
        let next = self.points.len() as u32;
        *self.ids.entry(key).or_insert_with(|| {
            self.points.push(DVec2::new(
                key[0] as f64 * QUANTUM_M,
                key[1] as f64 * QUANTUM_M,
            ));
            next
        })
    }

    fn edge(&mut self, a: u32, b: u32) {
        if a == b {
            return;
        }
        let (key, step) = if a < b { ((a, b), 1) } else { ((b, a), -1) };
        let count = self.edges.entry(key).or_insert(0);
        *count += step;
        if *count == 0 {
            self.edges.remove(&key);
        }
    }

    /// Adds the closed polygon `poly` (its last point joins its first), as it is oriented.
    pub fn add(&mut self, poly: impl IntoIterator<Item = DVec2>) {
        let mut first = None;
        let mut last = None;
        for p in poly {
            let id = self.id(p);
            match last {
                None => first = Some(id),
                Some(l) => self.edge(l, id),
            }
            last = Some(id);
        }
        if let (Some(f), Some(l)) = (first, last) {
            self.edge(l, f);
        }
    }

    /// The number of edges left (an edge added twice the same way counts twice).
    pub fn len(&self) -> usize {
        self.edges.values().map(|c| c.unsigned_abs() as usize).sum()
    }

    /// True when every edge cancelled (or none was added).
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty()
    }

    /// The edges left as closed loops of points (`[x, y]`, the last joining the first), in a
    /// fixed order whatever the order polygons were added in.
    pub fn loops(&self) -> Vec<Vec<[f64; 2]>> {
        // Directed edges, by where they start, in the order of the points' positions.
        let mut directed: Vec<(u32, u32)> = Vec::with_capacity(self.len());
        for (&(lo, hi), &count) in &self.edges {
            let e = if count > 0 { (lo, hi) } else { (hi, lo) };
            for _ in 0..count.unsigned_abs() {
                directed.push(e);
            }
        }
        let pos = |i: u32| {
            let p = self.points[i as usize];
            (p.x, p.y)
        };
        let order = |a: &(u32, u32), b: &(u32, u32)| {
            let (a0, a1, b0, b1) = (pos(a.0), pos(a.1), pos(b.0), pos(b.1));
            a0.0.total_cmp(&b0.0)
                .then(a0.1.total_cmp(&b0.1))
                .then(a1.0.total_cmp(&b1.0))
                .then(a1.1.total_cmp(&b1.1))
        };
        directed.sort_unstable_by(order);
        // Out-edges of each point: a contiguous run of `directed`, used front to back.
        let mut next = vec![0usize; self.points.len()];
        let mut end = vec![0usize; self.points.len()];
        for (k, &(a, _)) in directed.iter().enumerate().rev() {
            next[a as usize] = k;
            end[a as usize] = end[a as usize].max(k + 1);
        }
        let mut out = Vec::new();
        for k in 0..directed.len() {
            let origin = directed[k].0 as usize;
            // Every loop starts at the first unused out-edge of a point, in order.
            while next[origin] < end[origin] {
                let mut ring = Vec::new();
                let mut at = origin;
                // Every polygon added is closed, so a walk can only end where it started.
                while next[at] < end[at] {
                    let e = directed[next[at]];
                    next[at] += 1;
                    let p = self.points[at];
                    ring.push([p.x, p.y]);
                    at = e.1 as usize;
                    if at == origin {
                        break;
                    }
                }
                if ring.len() >= 3 {
                    out.push(ring);
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, ccw: bool) -> Vec<DVec2> {
        let mut s = vec![
            DVec2::new(x, y),
            DVec2::new(x + 1.0, y),
            DVec2::new(x + 1.0, y + 1.0),
            DVec2::new(x, y + 1.0),
        ];
        if !ccw {
            s.reverse();
        }
        s
    }

    #[test]
    fn neighbours_cancel_to_their_outline_and_opposites_to_nothing() {
        // A 3 x 2 block of unit squares, each as two triangles: 12 triangles, 36 edges; the
        // outline has 10 unit edges.
        let mut c = WindingChain::new();
        for i in 0..3 {
            for j in 0..2 {
                let s = square(i as f64, j as f64, true);
                c.add([s[0], s[1], s[2]]);
                c.add([s[0], s[2], s[3]]);
            }
        }
        assert_eq!(c.len(), 10);
        let loops = c.loops();
        assert_eq!(loops.len(), 1);
        assert_eq!(loops[0].len(), 10);
        let ring: Vec<DVec2> = loops[0].iter().map(|p| DVec2::new(p[0], p[1])).collect();
        assert!((crate::polygon::signed_area(&ring) - 6.0).abs() < 1e-9);
        // The top and bottom of a box: nothing left.
        let mut c = WindingChain::new();
        c.add(square(0.0, 0.0, true));
        c.add(square(0.0, 0.0, false));
        assert!(c.is_empty());
        assert!(c.loops().is_empty());
        // Two squares on top of each other the same way: each edge twice, two loops.
        let mut c = WindingChain::new();
        c.add(square(0.0, 0.0, true));
        c.add(square(1e-9, 0.0, true));
        assert_eq!(c.len(), 8);
        assert_eq!(c.loops().len(), 2);
    }
}

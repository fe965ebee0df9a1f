//! Lines in a floor-plan section: what a surface or a sheet leaves where it crosses the band.
//!
//! A fence or a glass balustrade modelled as a surface (an extruded open profile, a surface
//! model), or a sheet of an open mesh, crosses the band of a floor plan as a vertical face:
//! its part inside the band projects on XY to a segment, of (almost) no area, which the
//! section's area terms lose (and the sliver opening would remove anyway). For a robot it is a
//! wall. Such parts are kept as lines: each band part whose projection is thinner than
//! [`THIN_M`] gives the segment it lies along, and the segments are drawn [`LINE_WIDTH_M`]
//! wide (square ends, reaching half that past each end): an area the sliver opening keeps,
//! within half a centimetre of the surface, which the simulator's rays hit where the surface
//! is. The navigation grid marks every cell such a line touches (its rasteriser draws parts
//! thinner than a cell conservatively), so no route crosses it.
//!
//! The vertical faces of a closed solid lie on or inside its exact section; which of them are
//! lines is decided by [`crate::section`] (those outside the solid's section only, `Cover`),
//! so solids are drawn as before; a mesh whose edges pair up (a closed surface) is not searched.

use glam::{DVec2, DVec3};
use rustc_hash::FxHashSet;

use crate::polygon;
use crate::region::{self, Region};
use crate::section::SLIVER_M;

/// How wide lines are drawn, metres: five times the thinnest part a section keeps (2 x
/// [`SLIVER_M`]), thin beside anything a robot measures.
pub const LINE_WIDTH_M: f64 = 0.01;

/// Band parts whose projection is thinner than this (metres) are lines: the section's
/// sliver opening ([`SLIVER_M`]) would remove them.
pub const THIN_M: f64 = 2.0 * SLIVER_M;

/// Grid on which segment ends are compared to drop repeats, metres: the one section outlines'
/// points are merged on.
const QUANTUM_M: f64 = crate::winding_chain::QUANTUM_M;

/// Segments, each once (either direction), in the order first met.
#[derive(Debug, Default)]
pub(crate) struct Lines {
    segments: Vec<[DVec2; 2]>,
    seen: FxHashSet<[i64; 4]>,
}

impl Lines {
    /// Adds the segment `poly` (a convex polygon, a triangle's band part, whose projection on
    /// XY has the signed `area`) lies along when that projection is thinner than [`THIN_M`]
    /// and long and narrow (at most a tenth as thick as long); true when it did.
    pub(crate) fn add_if_thin(&mut self, poly: &[DVec3], area: f64) -> bool {
        // A convex polygon is at least area / diameter thick, and its diameter is at most its
        // box's diagonal: most faces (not vertical) stop here.
        let (lo, hi) = poly
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.truncate()), hi.max(p.truncate()))
            });
        if area.abs() >= THIN_M * lo.distance(hi) {
            return false;
        }
        let Some((a, b, thickness)) = thin_extent(poly.iter().map(|p| p.truncate())) else {
            return false;
        };
        if thickness >= THIN_M || thickness > 0.1 * a.distance(b) {
            return false;
        }
        self.add(a, b);
        true
    }

    /// Adds the segment `a`-`b` unless it is there already.
    pub(crate) fn add(&mut self, a: DVec2, b: DVec2) {
        if self.seen.insert(key(a, b)) {
            self.segments.push([a, b]);
        }
    }

    /// Number of segments.
    pub(crate) fn len(&self) -> usize {
        self.segments.len()
    }

    /// True when there is none.
    pub(crate) fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// Keeps the segments for which `keep` is true.
    pub(crate) fn retain(&mut self, mut keep: impl FnMut(DVec2, DVec2) -> bool) {
        self.segments.retain(|[a, b]| keep(*a, *b));
    }

    /// The segments drawn [`LINE_WIDTH_M`] wide, united.
    pub(crate) fn regions(&self) -> Vec<Region> {
        region::strokes(&self.segments, LINE_WIDTH_M)
    }
}

/// How far from a region a point may be and still be on it, metres (sections' points are
/// merged on 0.1 µm).
const ON_REGION_M: f64 = 1e-5;

/// The boundary edges of regions (which do not overlap, as a section's) bucketed on a grid of
/// about as many cells as edges, for asking whether points lie on them in about
/// `O(sqrt(edges))` per point rather than `O(edges)`, so that testing every side face of a dense
/// solid stays cheap. Coordinates are swapped when the regions are wider than tall, so rays
/// for the inside test run across the short side.
#[derive(Debug)]
pub(crate) struct Cover {
    edges: Vec<[DVec2; 2]>,
    swap: bool,
    lo: DVec2,
    hi: DVec2,
    cell: DVec2,
    cols: usize,
    rows: usize,
    /// Per cell (row-major), the edges whose box (grown by [`ON_REGION_M`]) meets it:
    /// bucket `i` holds `edge_ids[starts[i]..starts[i + 1]]` (one allocation for all, not
    /// one per bucket: a plan builds a cover for most meshes in the band).
    starts: Vec<u32>,
    edge_ids: Vec<u32>,
}

impl Cover {
    /// The index of `regions`' edges.
    pub(crate) fn new(regions: &[Region]) -> Cover {
        let mut edges: Vec<[DVec2; 2]> = Vec::new();
        for ring in regions.iter().flat_map(Region::rings) {
            let n = ring.len();
            edges.extend((0..n).map(|i| [ring[i], ring[(i + 1) % n]]));
        }
        let e = DVec2::splat(ON_REGION_M);
        let (lo, hi) = edges
            .iter()
            .flatten()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let swap = hi.x - lo.x > hi.y - lo.y;
        let t = |p: DVec2| if swap { DVec2::new(p.y, p.x) } else { p };
        for edge in &mut edges {
            *edge = edge.map(t);
        }
        let (lo, hi) = (t(lo) - e, t(hi) + e);
        // Few columns (the short side), about as many cells as edges.
        let n = edges.len().max(1) as f64;
        let size = hi - lo;
        let cols = if size.is_finite() && size.x > 0.0 {
            (n * size.x / size.y).sqrt().ceil().clamp(1.0, 1024.0)
        } else {
            1.0
        };
        let rows = (n / cols).ceil().clamp(1.0, 4096.0);
        let cell = if size.is_finite() {
            (size / DVec2::new(cols, rows)).max(DVec2::splat(1e-9))
        } else {
            DVec2::ONE
        };
        let (cols, rows) = (cols as usize, rows as usize);
        let mut cover = Cover {
            edges,
            swap,
            lo,
            hi,
            cell,
            cols,
            rows,
            starts: vec![0; cols * rows + 1],
            edge_ids: Vec::new(),
        };
        // Counted, then placed (the cells each edge's box meets, twice).
        let spans: Vec<((usize, usize), (usize, usize))> = cover
            .edges
            .iter()
            .map(|[a, b]| (cover.cell_of(a.min(*b) - e), cover.cell_of(a.max(*b) + e)))
            .collect();
        for &((c0, r0), (c1, r1)) in &spans {
            for r in r0..=r1 {
                for c in c0..=c1 {
                    cover.starts[r * cols + c + 1] += 1;
                }
            }
        }
        for i in 0..cols * rows {
            cover.starts[i + 1] += cover.starts[i];
        }
        let mut next: Vec<u32> = cover.starts[..cols * rows].to_vec();
        cover.edge_ids = vec![0; cover.starts[cols * rows] as usize];
        for (k, &((c0, r0), (c1, r1))) in spans.iter().enumerate() {
            for r in r0..=r1 {
                for c in c0..=c1 {
                    let slot = &mut next[r * cols + c];
                    cover.edge_ids[*slot as usize] = k as u32;
                    *slot += 1;
                }
            }
        }
        cover
    }

    /// The edges of bucket `i`.
    fn bucket(&self, i: usize) -> &[u32] {
        &self.edge_ids[self.starts[i] as usize..self.starts[i + 1] as usize]
    }

    /// The cell holding `p` (swapped coordinates), clamped to the grid.
    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let q = ((p - self.lo) / self.cell).floor();
        let clamp = |v: f64, n: usize| (v.max(0.0) as usize).min(n - 1);
        (clamp(q.x, self.cols), clamp(q.y, self.rows))
    }

    /// True when `p` is inside the regions or within [`ON_REGION_M`] of their boundary.
    pub(crate) fn holds(&self, p: DVec2) -> bool {
        if self.edges.is_empty() || !p.is_finite() {
            return false;
        }
        let p = if self.swap { DVec2::new(p.y, p.x) } else { p };
        if p.cmplt(self.lo).any() || p.cmpgt(self.hi).any() {
            return false;
        }
        let (c, r) = self.cell_of(p);
        let near = self.bucket(r * self.cols + c).iter().any(|&k| {
            let [a, b] = self.edges[k as usize];
            polygon::segment_distance(a, b, p) <= ON_REGION_M
        });
        if near {
            return true;
        }
        // Even-odd along +x: each edge crossing the ray counted in the cell its crossing is in.
        let mut inside = false;
        for cc in c..self.cols {
            for &k in self.bucket(r * self.cols + cc) {
                let [a, b] = self.edges[k as usize];
                if (a.y > p.y) == (b.y > p.y) {
                    continue;
                }
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if x > p.x && self.cell_of(DVec2::new(x, p.y)).0 == cc {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// True when the segment `a`-`b` lies on the regions: its ends and its middle.
    pub(crate) fn holds_segment(&self, a: DVec2, b: DVec2) -> bool {
        self.holds(a) && self.holds(b) && self.holds((a + b) / 2.0)
    }

    #[cfg(test)]
    fn largest_bucket(&self) -> usize {
        self.starts
            .windows(2)
            .map(|w| (w[1] - w[0]) as usize)
            .max()
            .unwrap_or(0)
    }
}

/// `p` on the grid of [`QUANTUM_M`].
fn grid_point(p: DVec2) -> [i64; 2] {
    [
        (p.x / QUANTUM_M).round() as i64,
        (p.y / QUANTUM_M).round() as i64,
    ]
}

/// The segment `a`-`b` either way round, its ends on the grid of [`QUANTUM_M`].
fn key(a: DVec2, b: DVec2) -> [i64; 4] {
    let (qa, qb) = (grid_point(a), grid_point(b));
    if qa <= qb {
        [qa[0], qa[1], qb[0], qb[1]]
    } else {
        [qb[0], qb[1], qa[0], qa[1]]
    }
}

/// The two points of `points` farthest apart and the greatest distance of any point from the
/// line through them; `None` for fewer than two distinct points.
fn thin_extent(points: impl Iterator<Item = DVec2> + Clone) -> Option<(DVec2, DVec2, f64)> {
    let mut best: Option<(DVec2, DVec2, f64)> = None;
    for (i, p) in points.clone().enumerate() {
        for q in points.clone().skip(i + 1) {
            let d = p.distance_squared(q);
            if best.is_none_or(|(_, _, b)| d > b) {
                best = Some((p, q, d));
            }
        }
    }
    let (a, b, d) = best?;
    if d.is_nan() || d <= 0.0 {
        return None;
    }
    let dir = (b - a) / d.sqrt();
    let thickness = points
        .map(|p| dir.perp_dot(p - a).abs())
        .fold(0.0, f64::max);
    Some((a, b, thickness))
}

/// The convex hull of `points` as a region; when it has no area (the points lie on a line, as
/// a vertical sheet's do), the segment between the two farthest apart drawn
/// [`LINE_WIDTH_M`] wide. Empty for fewer than two distinct points.
pub(crate) fn hull_or_line(points: &[DVec2]) -> Vec<Region> {
    let hull = polygon::convex_hull(points);
    if hull.len() >= 3 {
        if let Some(r) = Region::from_ring(hull.clone()) {
            return vec![r];
        }
    }
    match thin_extent(hull.iter().copied()) {
        Some((a, b, _)) => region::strokes(&[[a, b]], LINE_WIDTH_M),
        None => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_vertical_triangle_is_a_line_and_a_flat_one_is_not() {
        let mut lines = Lines::default();
        let wall = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(2.0, 1.0, 1.0),
        ];
        assert!(lines.add_if_thin(&wall, 0.0));
        // The same segment the other way round is there already.
        let back = [wall[1], wall[0], DVec3::new(0.0, 0.0, 1.0)];
        assert!(lines.add_if_thin(&back, 0.0));
        assert_eq!(lines.len(), 1);
        // Flat, small or not: no line.
        let flat = [
            DVec3::ZERO,
            DVec3::new(0.001, 0.0, 0.0),
            DVec3::new(0.0, 0.001, 0.0),
        ];
        assert!(!lines.add_if_thin(&flat, 0.5e-6));
        assert!(!lines.add_if_thin(&flat, 0.0));
        // A vertical edge seen end on (a point): no line.
        let pole = [
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(0.0, 0.0, 0.5),
        ];
        assert!(!lines.add_if_thin(&pole, 0.0));
        let r = lines.regions();
        assert_eq!(r.len(), 1);
        // sqrt(5) m long plus half the width at either end, the width across.
        let want = (5f64.sqrt() + LINE_WIDTH_M) * LINE_WIDTH_M;
        assert!(
            (region::total_area(&r) - want).abs() < 1e-6,
            "{}",
            r[0].area()
        );
        assert!(r[0].contains(DVec2::new(1.0, 0.5)));
        assert!(!r[0].contains(DVec2::new(1.0, 0.5 + LINE_WIDTH_M)));
    }

    #[test]
    fn the_cover_holds_what_is_in_a_region_or_on_its_boundary() {
        let ring = |c: [(f64, f64); 4]| c.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
        let square = Region {
            outer: ring([(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]),
            holes: vec![ring([(1.0, 1.0), (1.0, 3.0), (3.0, 3.0), (3.0, 1.0)])],
        };
        let far = Region::from_ring(ring([(10.0, 0.0), (11.0, 0.0), (11.0, 1.0), (10.0, 1.0)]));
        let regions = [square, far.unwrap()];
        let cover = Cover::new(&regions);
        // Inside, on the boundary (outer, hole, corner), within 10 µm; in the hole, outside.
        for p in [
            (0.5, 0.5),
            (3.5, 2.0),
            (4.0, 2.0),
            (1.0, 2.0),
            (0.0, 0.0),
            (10.5, 0.5),
        ] {
            assert!(cover.holds(DVec2::new(p.0, p.1)), "{p:?}");
        }
        assert!(cover.holds(DVec2::new(4.000_005, 2.0)));
        for p in [
            (2.0, 2.0),
            (4.001, 2.0),
            (7.0, 0.5),
            (-1.0, 2.0),
            (12.0, 0.5),
            (2.0, 5.0),
        ] {
            assert!(!cover.holds(DVec2::new(p.0, p.1)), "{p:?}");
        }
        // As the brute force says on a grid of points.
        for i in 0..=120 {
            for j in 0..=50 {
                let p = DVec2::new(
                    -0.5 + 0.1 * i as f64 + 0.0123,
                    -0.5 + 0.1 * j as f64 + 0.0071,
                );
                let brute = regions.iter().any(|r| r.contains(p));
                assert_eq!(cover.holds(p), brute, "{p}");
            }
        }
        assert!(cover.holds_segment(DVec2::new(0.0, 0.0), DVec2::new(4.0, 0.0)));
        assert!(!cover.holds_segment(DVec2::new(0.0, 2.0), DVec2::new(4.0, 2.0)));
        assert!(!Cover::new(&[]).holds(DVec2::ZERO));
        // A long thin region of 2,000 edges (a bar's section): small buckets either way round.
        for swap in [false, true] {
            let mut outer: Vec<DVec2> = (0..1000)
                .map(|i| DVec2::new(1.5 * i as f64 / 999.0, 0.0))
                .chain((0..1000).map(|i| DVec2::new(1.5 * (999 - i) as f64 / 999.0, 0.03)))
                .collect();
            if swap {
                outer = outer
                    .into_iter()
                    .map(|p| DVec2::new(p.y, p.x))
                    .rev()
                    .collect();
            }
            let cover = Cover::new(&[Region {
                outer,
                holes: Vec::new(),
            }]);
            assert!(cover.largest_bucket() <= 8, "{}", cover.largest_bucket());
            let p = |x: f64, y: f64| {
                if swap {
                    DVec2::new(y, x)
                } else {
                    DVec2::new(x, y)
                }
            };
            assert!(cover.holds(p(0.7, 0.015)) && cover.holds(p(0.7, 0.0)));
            assert!(!cover.holds(p(0.7, 0.031)) && !cover.holds(p(1.6, 0.015)));
        }
    }

    #[test]
    fn a_hull_without_area_is_a_line() {
        let on_a_line = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(3.0, 0.0),
        ];
        let r = hull_or_line(&on_a_line);
        assert_eq!(r.len(), 1);
        assert!((r[0].area() - (3.0 + LINE_WIDTH_M) * LINE_WIDTH_M).abs() < 1e-6);
        let square = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        assert!((hull_or_line(&square)[0].area() - 1.0).abs() < 1e-12);
        assert!(hull_or_line(&[DVec2::ZERO, DVec2::ZERO]).is_empty());
    }
}

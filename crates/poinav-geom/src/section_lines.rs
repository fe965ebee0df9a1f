//! Lines in a floor-plan section: what a surface or a sheet leaves where it crosses the band.
//!
//! A fence or a glass balustrade modelled as a surface (an extruded open profile, a surface
//! model), or a sheet of an open mesh, crosses the band of a floor plan as a vertical face:
//! its part inside the band projects on XY to a segment, of (almost) no area, which the
//! section's area terms lose (and the sliver opening would remove anyway). For a robot it is a
//! wall. Such parts are kept as lines: each band part whose projection is thinner than
//! [`THIN_M`] gives the segment it lies along, and the segments are drawn [`LINE_WIDTH_M`]
//! wide (square ends, reaching half that past each end), wider than the default 5 cm cells of
//! the navigation grid, so every row and column of cells that crosses a line has a cell
//! centre on it.
//!
//! The vertical faces of a closed solid lie on or inside its exact section; which of them are
//! lines is decided by [`crate::section`] (those outside the solid's section only), so solids
//! are drawn as before.

use glam::{DVec2, DVec3};
use rustc_hash::FxHashSet;

use crate::polygon;
use crate::region::{self, Region};
use crate::section::SLIVER_M;

/// How wide lines are drawn, metres: more than the navigation grid's default 5 cm cells.
pub const LINE_WIDTH_M: f64 = 0.06;

/// Band parts whose projection is thinner than this (metres) are lines: the section's
/// sliver opening ([`SLIVER_M`]) would remove them.
pub const THIN_M: f64 = 2.0 * SLIVER_M;

/// Grid on which segment ends are compared to drop repeats, metres.
const QUANTUM_M: f64 = 1e-7;

/// Segments, each once (either direction), in the order first met.
#[derive(Debug, Default)]
pub(crate) struct Lines {
    segments: Vec<[DVec2; 2]>,
    seen: FxHashSet<[i64; 4]>,
}

impl Lines {
    /// Adds the segment `poly` (a convex polygon, a triangle's band part) lies along when its
    /// projection on XY is thinner than [`THIN_M`] and long and narrow (at most a tenth as
    /// thick as long); true when it did.
    pub(crate) fn add_if_thin(&mut self, poly: &[DVec3]) -> bool {
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
        let q = |p: DVec2| {
            [
                (p.x / QUANTUM_M).round() as i64,
                (p.y / QUANTUM_M).round() as i64,
            ]
        };
        let (qa, qb) = (q(a), q(b));
        let key = if qa <= qb {
            [qa[0], qa[1], qb[0], qb[1]]
        } else {
            [qb[0], qb[1], qa[0], qa[1]]
        };
        if self.seen.insert(key) {
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
        assert!(lines.add_if_thin(&wall));
        // The same segment the other way round is there already.
        let back = [wall[1], wall[0], DVec3::new(0.0, 0.0, 1.0)];
        assert!(lines.add_if_thin(&back));
        assert_eq!(lines.len(), 1);
        // Flat, small or not: no line.
        let flat = [
            DVec3::ZERO,
            DVec3::new(0.001, 0.0, 0.0),
            DVec3::new(0.0, 0.001, 0.0),
        ];
        assert!(!lines.add_if_thin(&flat));
        // A vertical edge seen end on (a point): no line.
        let pole = [
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(0.0, 0.0, 0.5),
        ];
        assert!(!lines.add_if_thin(&pole));
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

//! Plane regions: polygons with holes in world XY metres, and their boolean operations (union,
//! difference, intersection) through the `i_overlay` crate.
//!
//! `i_overlay` snaps coordinates to an integer grid fitted to the operands' bounding box
//! (2^30 steps across it: 0.1 µm for a 100 m building), so results are exact to well below a
//! millimetre; outer rings come out counter-clockwise, holes clockwise, collinear points
//! removed.

use glam::DVec2;
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::overlay::FloatOverlay;
use i_overlay::mesh::outline::offset::OutlineOffset;
use i_overlay::mesh::stroke::offset::StrokeOffset;
use i_overlay::mesh::style::{LineCap, LineJoin, OutlineStyle, StrokeStyle};
use serde::{Deserialize, Serialize};

use crate::polygon;

/// A polygon with holes: one counter-clockwise outer ring and clockwise holes, none repeating
/// its first point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Region {
    /// The outer boundary, counter-clockwise.
    pub outer: Vec<DVec2>,
    /// Holes, clockwise.
    pub holes: Vec<Vec<DVec2>>,
}

impl Region {
    /// A region without holes from a ring of either orientation; `None` when it has no area.
    pub fn from_ring(ring: Vec<DVec2>) -> Option<Region> {
        Some(Region {
            outer: polygon::clean(ring)?,
            holes: Vec::new(),
        })
    }

    /// The enclosed area (outer ring less holes), square metres.
    pub fn area(&self) -> f64 {
        polygon::signed_area(&self.outer).abs()
            - self
                .holes
                .iter()
                .map(|h| polygon::signed_area(h).abs())
                .sum::<f64>()
    }

    /// True when `p` is inside the outer ring (or on it) and not strictly inside a hole.
    pub fn contains(&self, p: DVec2) -> bool {
        polygon::contains_closed(&self.outer, p)
            && !self
                .holes
                .iter()
                .any(|h| polygon::contains_closed(h, p) && polygon::boundary_distance(h, p) > 1e-12)
    }

    /// Every ring: the outer one first, then the holes.
    pub fn rings(&self) -> impl Iterator<Item = &Vec<DVec2>> {
        std::iter::once(&self.outer).chain(self.holes.iter())
    }

    /// The area centroid (holes subtracted).
    pub fn centroid(&self) -> DVec2 {
        let weighted = |ring: &[DVec2]| {
            let a = polygon::signed_area(ring).abs();
            (polygon::centroid(ring).unwrap_or_default() * a, a)
        };
        let (mut c, mut a) = weighted(&self.outer);
        for h in &self.holes {
            let (hc, ha) = weighted(h);
            c -= hc;
            a -= ha;
        }
        if a > 0.0 {
            c / a
        } else {
            polygon::centroid(&self.outer).unwrap_or_default()
        }
    }

    /// Smallest axis-aligned box (min, max) around the outer ring.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        polygon::bounds(&self.outer).unwrap_or_default()
    }

    /// True when the segment from `a` to `b` meets the region: an end inside it, or a
    /// crossing of one of its rings.
    pub fn meets_segment(&self, a: DVec2, b: DVec2) -> bool {
        if self.contains(a) || self.contains(b) {
            return true;
        }
        self.rings().any(|ring| {
            let n = ring.len();
            (0..n).any(|i| segments_meet(a, b, ring[i], ring[(i + 1) % n]))
        })
    }
}

/// True when the closed segments `a`-`b` and `c`-`d` have a point in common.
pub fn segments_meet(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let orient = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let on = |p: DVec2, q: DVec2, r: DVec2| {
        r.x >= p.x.min(q.x) && r.x <= p.x.max(q.x) && r.y >= p.y.min(q.y) && r.y <= p.y.max(q.y)
    };
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && on(c, d, a))
        || (d2 == 0.0 && on(c, d, b))
        || (d3 == 0.0 && on(a, b, c))
        || (d4 == 0.0 && on(a, b, d))
}

/// Total area of `regions` (they are assumed not to overlap).
pub fn total_area(regions: &[Region]) -> f64 {
    regions.iter().map(Region::area).sum()
}

/// The smallest axis-aligned box (min, max) around all regions; `None` when there is none.
pub fn bounds_of<'a>(regions: impl IntoIterator<Item = &'a Region>) -> Option<(DVec2, DVec2)> {
    regions.into_iter().fold(None, |acc, r| {
        let (lo, hi) = r.bounds();
        Some(match acc {
            None => (lo, hi),
            Some((a, b)) => (a.min(lo), b.max(hi)),
        })
    })
}

type Contour = Vec<[f64; 2]>;

/// Runs one `i_overlay` operation. `subject` and `clip` are rings, filled with the non-zero
/// rule each on its own, then combined by `rule`.
pub(crate) fn overlay_rings(
    subject: &[Contour],
    clip: &[Contour],
    rule: OverlayRule,
) -> Vec<Region> {
    if subject.is_empty() && clip.is_empty() {
        return Vec::new();
    }
    let shapes = FloatOverlay::with_subj_and_clip(&subject.to_vec(), &clip.to_vec())
        .overlay(rule, FillRule::NonZero);
    shapes.into_iter().filter_map(region_of).collect()
}

fn oriented(regions: &[Region]) -> Vec<Contour> {
    // Outer rings counter-clockwise and holes clockwise, so the non-zero rule fills each
    // region once whatever the caller's orientation.
    regions
        .iter()
        .flat_map(|r| {
            let outer = with_sign(&r.outer, true);
            let holes = r.holes.iter().map(|h| with_sign(h, false));
            std::iter::once(outer).chain(holes)
        })
        .collect()
}

fn with_sign(ring: &[DVec2], ccw: bool) -> Contour {
    let mut c: Contour = ring.iter().map(|p| [p.x, p.y]).collect();
    if (polygon::signed_area(ring) > 0.0) != ccw {
        c.reverse();
    }
    c
}

/// The union of `regions`, overlapping or not.
pub fn union(regions: &[Region]) -> Vec<Region> {
    overlay_rings(&oriented(regions), &[], OverlayRule::Subject)
}

/// `a` less `b`.
pub fn difference(a: &[Region], b: &[Region]) -> Vec<Region> {
    if b.is_empty() {
        return union(a);
    }
    overlay_rings(&oriented(a), &oriented(b), OverlayRule::Difference)
}

/// The parts common to `a` and `b`.
pub fn intersection(a: &[Region], b: &[Region]) -> Vec<Region> {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    overlay_rings(&oriented(a), &oriented(b), OverlayRule::Intersect)
}

/// `regions` with every part thinner than `2 * eps` removed (a morphological opening: shrunk
/// by `eps`, then grown back with mitred corners, so right-angled outlines come back as they
/// were). Slivers that booleans leave along coplanar faces go; walls and leaves stay.
pub fn open(regions: &[Region], eps: f64) -> Vec<Region> {
    if regions.is_empty() || eps.is_nan() || eps <= 0.0 {
        return regions.to_vec();
    }
    let shapes: Vec<Vec<Contour>> = regions
        .iter()
        .map(|r| {
            let outer = with_sign(&r.outer, true);
            std::iter::once(outer)
                .chain(r.holes.iter().map(|h| with_sign(h, false)))
                .collect()
        })
        .collect();
    let join = || LineJoin::Miter(0.01 * std::f64::consts::PI);
    let shrunk = shapes.outline(&OutlineStyle::new(-eps).line_join(join()));
    if shrunk.is_empty() {
        return Vec::new();
    }
    let grown = shrunk.outline(&OutlineStyle::new(eps).line_join(join()));
    grown.into_iter().filter_map(region_of).collect()
}

/// The segments `a`-`b` drawn `width` wide, with square ends reaching `width / 2` past each
/// end, united. Segments of no length are left out.
pub fn strokes(segments: &[[DVec2; 2]], width: f64) -> Vec<Region> {
    let paths: Vec<Contour> = segments
        .iter()
        .filter(|[a, b]| a.distance(*b) > 0.0 && a.is_finite() && b.is_finite())
        .map(|[a, b]| vec![[a.x, a.y], [b.x, b.y]])
        .collect();
    if paths.is_empty() || width.is_nan() || width <= 0.0 {
        return Vec::new();
    }
    let style = StrokeStyle::new(width)
        .start_cap(LineCap::Square)
        .end_cap(LineCap::Square);
    paths
        .stroke(style, false)
        .into_iter()
        .filter_map(region_of)
        .collect()
}

fn region_of(shape: Vec<Contour>) -> Option<Region> {
    let mut rings = shape
        .into_iter()
        .map(|c| c.into_iter().map(|[x, y]| DVec2::new(x, y)).collect());
    let outer: Vec<DVec2> = rings.next()?;
    if outer.len() < 3 {
        return None;
    }
    let holes = rings.filter(|h: &Vec<DVec2>| h.len() >= 3).collect();
    Some(Region { outer, holes })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Region {
        Region::from_ring(vec![
            DVec2::new(x0, y0),
            DVec2::new(x1, y0),
            DVec2::new(x1, y1),
            DVec2::new(x0, y1),
        ])
        .unwrap()
    }

    #[test]
    fn a_door_gap_cut_from_a_wall() {
        let wall = rect(0.0, 0.0, 10.0, 0.2);
        let opening = rect(4.0, -0.1, 4.9, 0.3);
        let cut = difference(std::slice::from_ref(&wall), std::slice::from_ref(&opening));
        assert_eq!(cut.len(), 2);
        assert!(
            (total_area(&cut) - (10.0 - 0.9) * 0.2).abs() < 1e-6,
            "{}",
            total_area(&cut)
        );
        assert!(cut.iter().all(|r| !r.contains(DVec2::new(4.45, 0.1))));
        assert!(cut
            .iter()
            .all(|r| !r.meets_segment(DVec2::new(4.1, -1.0), DVec2::new(4.1, 1.0))));
        assert!(cut
            .iter()
            .any(|r| r.meets_segment(DVec2::new(3.9, -1.0), DVec2::new(3.9, 1.0))));
        let common = intersection(&[wall], &[opening]);
        assert_eq!(common.len(), 1);
        assert!((common[0].area() - 0.18).abs() < 1e-6);
    }

    #[test]
    fn union_of_either_orientation_and_a_hole() {
        let mut a = rect(0.0, 0.0, 2.0, 2.0);
        a.outer.reverse();
        let b = rect(1.0, 1.0, 3.0, 3.0);
        let u = union(&[a, b]);
        assert_eq!(u.len(), 1);
        assert!((u[0].area() - 7.0).abs() < 1e-6);
        let ring = difference(&[rect(0.0, 0.0, 4.0, 4.0)], &[rect(1.0, 1.0, 3.0, 3.0)]);
        assert_eq!(ring.len(), 1);
        assert_eq!(ring[0].holes.len(), 1);
        assert!((ring[0].area() - 12.0).abs() < 1e-6);
        assert!(!ring[0].contains(DVec2::new(2.0, 2.0)));
        assert!(ring[0].contains(DVec2::new(0.5, 2.0)));
        assert!(polygon::signed_area(&ring[0].outer) > 0.0);
        assert!(polygon::signed_area(&ring[0].holes[0]) < 0.0);
        assert!((ring[0].centroid() - DVec2::new(2.0, 2.0)).length() < 1e-6);
    }

    #[test]
    fn opening_removes_a_sliver_and_keeps_corners() {
        // A wall with a 0.1 mm thin sliver running 0.6 m into its door gap.
        let wall = Region::from_ring(vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(4.6, 0.0),
            DVec2::new(4.6, 0.0001),
            DVec2::new(4.0, 0.0001),
            DVec2::new(4.0, 0.2),
            DVec2::new(0.0, 0.2),
        ])
        .unwrap();
        let ring = difference(&[rect(10.0, 0.0, 14.0, 4.0)], &[rect(11.0, 1.0, 13.0, 3.0)]);
        let opened = open(&[wall, ring[0].clone()], 0.001);
        assert_eq!(opened.len(), 2);
        let small = opened.iter().find(|r| r.bounds().0.x < 5.0).unwrap();
        let (lo, hi) = small.bounds();
        assert!((hi.x - 4.0).abs() < 1e-6 && lo.x.abs() < 1e-6, "{lo} {hi}");
        assert!(
            (total_area(&opened) - 0.8 - 12.0).abs() < 1e-6,
            "{}",
            total_area(&opened)
        );
        assert_eq!(opened.iter().map(|r| r.holes.len()).sum::<usize>(), 1);
        assert!(open(&[rect(0.0, 0.0, 1.0, 0.0015)], 0.001).is_empty());
    }

    #[test]
    fn strokes_unite_and_reach_past_their_ends() {
        let l = strokes(
            &[
                [DVec2::new(0.0, 2.0), DVec2::new(2.5, 2.0)],
                [DVec2::new(2.5, 2.0), DVec2::new(2.5, 5.0)],
                [DVec2::new(1.0, 1.0), DVec2::new(1.0, 1.0)],
            ],
            0.06,
        );
        assert_eq!(l.len(), 1);
        let want = 2.56 * 0.06 + 3.06 * 0.06 - 0.06 * 0.06;
        assert!((total_area(&l) - want).abs() < 1e-6, "{}", total_area(&l));
        assert!(strokes(&[], 0.06).is_empty());
    }
}

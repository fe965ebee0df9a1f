//! Measures and predicates of one ring: signed area, area centroid, bounding box,
//! containment (even-odd, or counting the boundary in), the crossings of a horizontal line
//! and a point inside.

use glam::DVec2;

use crate::distance::boundary_distance;

/// Signed area: positive for counter-clockwise rings, 0 for fewer than three points.
pub fn signed_area(ring: &[DVec2]) -> f64 {
    let n = ring.len();
    if n < 3 {
        return 0.0;
    }
    // Shift to the first point so large world coordinates lose no precision.
    let o = ring[0];
    (0..n)
        .map(|i| (ring[i] - o).perp_dot(ring[(i + 1) % n] - o))
        .sum::<f64>()
        / 2.0
}

/// The smallest axis-aligned box around the points, as (min, max); `None` when empty.
pub fn bounds(points: &[DVec2]) -> Option<(DVec2, DVec2)> {
    bounds_of(points)
}

/// [`bounds`] of any points, such as every ring of an element or a floor
/// (`rings.iter().flat_map(|r| r.iter())`).
pub fn bounds_of<'a>(points: impl IntoIterator<Item = &'a DVec2>) -> Option<(DVec2, DVec2)> {
    let mut points = points.into_iter();
    let first = *points.next()?;
    Some(points.fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))))
}

/// The area centroid (the mean of the vertices when the ring has no area); `None` when empty.
/// Computed about the ring's first point, so large world coordinates lose no precision.
pub fn centroid(ring: &[DVec2]) -> Option<DVec2> {
    centroid_about(ring, *ring.first()?)
}

/// [`centroid`] computed with the coordinates taken relative to `o`: the result does not
/// depend on `o` but its rounding does (the nearer `o` is to the ring, the fewer bits are
/// lost). [`interior_point`] uses the world origin.
pub fn centroid_about(ring: &[DVec2], o: DVec2) -> Option<DVec2> {
    let n = ring.len();
    let (lo, hi) = bounds(ring)?;
    let (mut a, mut c) = (0.0, DVec2::ZERO);
    for i in 0..n {
        let (p, q) = (ring[i] - o, ring[(i + 1) % n] - o);
        let w = p.perp_dot(q);
        a += w;
        c += (p + q) * w;
    }
    let extent = (hi - lo).max_element();
    if a.abs() <= 1e-12 * extent * extent {
        return Some(ring.iter().copied().sum::<DVec2>() / n as f64);
    }
    Some(o + c / (3.0 * a))
}

/// True when `p` is inside `ring` (even-odd rule; a point exactly on an edge may go either
/// way). [`contains_closed`] counts the boundary in.
#[inline]
pub fn contains(ring: &[DVec2], p: DVec2) -> bool {
    let n = ring.len();
    if n < 3 {
        return false;
    }
    let mut inside = false;
    let mut j = n - 1;
    for i in 0..n {
        let (a, b) = (ring[i], ring[j]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                inside = !inside;
            }
        }
        j = i;
    }
    inside
}

/// True when `p` is inside `ring` or on its boundary (within 1e-12 of `p`'s magnitude, at
/// least 1e-12), else by the even-odd rule.
pub fn contains_closed(ring: &[DVec2], p: DVec2) -> bool {
    ring.len() >= 3
        && (boundary_distance(ring, p) <= 1e-12 * p.length().max(1.0) || contains(ring, p))
}

/// X coordinates where the horizontal line at `y` crosses the ring's edges (half-open rule, so a
/// vertex is counted once).
pub fn crossings(ring: &[DVec2], y: f64) -> Vec<f64> {
    let mut xs = Vec::new();
    crossings_into(ring, y, &mut xs);
    xs
}

/// [`crossings`] into `xs` (cleared first), for a caller that scans many lines with one buffer.
pub fn crossings_into(ring: &[DVec2], y: f64, xs: &mut Vec<f64>) {
    xs.clear();
    let n = ring.len();
    if n < 3 {
        return;
    }
    let mut j = n - 1;
    for i in 0..n {
        let (a, b) = (ring[j], ring[i]);
        if (a.y <= y) != (b.y <= y) {
            xs.push(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
        }
        j = i;
    }
}

/// A point inside the ring: its centroid when that is inside, else the middle of the widest
/// horizontal span through the centroid's height (or through the middle of the box).
///
/// The centroid is taken about the world origin ([`centroid_about`]), as navigation has
/// always placed its zone nodes, route ends and labels: about the first point it can differ
/// in the last bit, which moves a point on a grid line to the next cell and so changes routes
/// and maps.
pub fn interior_point(ring: &[DVec2]) -> Option<DVec2> {
    let c = centroid_about(ring, DVec2::ZERO)?;
    if contains(ring, c) {
        return Some(c);
    }
    let (lo, hi) = bounds(ring)?;
    let mut xs = Vec::new();
    for y in [
        c.y,
        (lo.y + hi.y) / 2.0,
        lo.y + (hi.y - lo.y) * 0.25,
        lo.y + (hi.y - lo.y) * 0.75,
    ] {
        crossings_into(ring, y, &mut xs);
        xs.sort_by(f64::total_cmp);
        let best = xs
            .chunks_exact(2)
            .map(|s| (s[0], s[1]))
            .max_by(|a, b| (a.1 - a.0).total_cmp(&(b.1 - b.0)));
        if let Some((x0, x1)) = best {
            if x1 > x0 {
                return Some(DVec2::new((x0 + x1) / 2.0, y));
            }
        }
    }
    Some(c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distance::{area_distance, boundary_distance};
    use crate::rect;

    fn l_shape() -> Vec<DVec2> {
        vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(4.0, 0.0),
            DVec2::new(4.0, 1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 3.0),
            DVec2::new(0.0, 3.0),
        ]
    }

    #[test]
    fn containment_area_and_centroid_of_a_square() {
        let s = rect(0.0, 0.0, 2.0, 2.0);
        assert!(contains(&s, DVec2::new(1.0, 1.0)));
        assert!(!contains(&s, DVec2::new(3.0, 1.0)));
        assert_eq!(signed_area(&s), 4.0);
        assert_eq!(centroid(&s), Some(DVec2::new(1.0, 1.0)));
        assert_eq!(area_distance(&s, DVec2::new(3.0, 1.0)), 1.0);
        assert_eq!(
            bounds(&s),
            Some((DVec2::new(0.0, 0.0), DVec2::new(2.0, 2.0)))
        );
        assert_eq!(bounds(&[]), None);
        assert_eq!(centroid(&[]), None);
    }

    #[test]
    fn point_in_polygon_for_an_l_shape() {
        let l = l_shape();
        assert!(contains_closed(&l, DVec2::new(0.5, 2.5)));
        assert!(contains_closed(&l, DVec2::new(3.5, 0.5)));
        assert!(!contains_closed(&l, DVec2::new(2.0, 2.0)), "in the notch");
        assert!(!contains(&l, DVec2::new(2.0, 2.0)), "in the notch");
        assert!(contains_closed(&l, DVec2::new(4.0, 0.5)), "on the boundary");
        assert!(!contains_closed(&l, DVec2::new(-0.1, 0.5)));
        assert!((boundary_distance(&l, DVec2::new(2.0, 2.0)) - 1.0).abs() < 1e-12);
        assert_eq!(signed_area(&l), 6.0);
        let c = centroid(&l).unwrap();
        // (4 * (2, 0.5) + 2 * (0.5, 2)) / 6, on the notch's lower edge.
        assert!(c.distance(DVec2::new(1.5, 1.0)) < 1e-12);
        assert!(contains_closed(&l, c));
    }

    #[test]
    fn an_interior_point_when_the_centroid_is_outside() {
        let l = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(4.0, 0.0),
            DVec2::new(4.0, 0.5),
            DVec2::new(0.5, 0.5),
            DVec2::new(0.5, 4.0),
            DVec2::new(0.0, 4.0),
        ];
        assert!(!contains(&l, centroid(&l).unwrap()));
        let p = interior_point(&l).unwrap();
        assert!(contains(&l, p));
        // The centroid's height is above the foot: the widest span there is the upright.
        assert!((p.x - 0.25).abs() < 1e-12, "{p}");
    }

    #[test]
    fn crossings_count_a_vertex_once() {
        let s = rect(0.0, 0.0, 2.0, 2.0);
        let mut xs = crossings(&s, 1.0);
        xs.sort_by(f64::total_cmp);
        assert_eq!(xs, vec![0.0, 2.0]);
        // Through the bottom corners: the half-open rule counts each vertical edge once.
        assert_eq!(crossings(&s, 0.0).len(), 2);
        assert!(crossings(&s, 2.5).is_empty());
    }

    #[test]
    fn far_from_the_origin_the_area_keeps_its_precision() {
        let far = DVec2::new(2.5e6, -1.25e6);
        let s: Vec<DVec2> = rect(0.0, 0.0, 0.1, 0.3).iter().map(|p| *p + far).collect();
        // Unshifted, the products of coordinates near 3e6 would lose about 1e-3 m^2.
        assert!((signed_area(&s) - 0.03).abs() < 1e-9);
        assert!(centroid(&s).unwrap().distance(far + DVec2::new(0.05, 0.15)) < 1e-9);
    }
}

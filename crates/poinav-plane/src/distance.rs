//! Distances in the plane, the shape first and the point last: from a point to a segment, to
//! a ring's boundary, to a ring as an area (0 inside), and between two rings as areas.

use glam::DVec2;

use crate::measure::contains;

/// Distance from `p` to the segment `a`-`b`.
#[inline]
pub fn segment_distance(a: DVec2, b: DVec2, p: DVec2) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// Distance from `p` to the ring's boundary (0 on the boundary, infinite for an empty ring).
#[inline]
pub fn boundary_distance(ring: &[DVec2], p: DVec2) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| segment_distance(ring[i], ring[(i + 1) % n], p))
        .fold(f64::INFINITY, f64::min)
}

/// Distance from `p` to the ring as an area: 0 inside.
pub fn area_distance(ring: &[DVec2], p: DVec2) -> f64 {
    if contains(ring, p) {
        0.0
    } else {
        boundary_distance(ring, p)
    }
}

/// Where the line `p + t * dir` crosses the line through segment `a`-`b`: `(t, u)` with the
/// crossing at `a + u * (b - a)` (on the segment for `u` in `[0, 1]`; ahead of `p` for
/// `t >= 0`, in units of `dir`); `None` when they are parallel (`|dir x (b - a)| < 1e-12`).
#[inline]
pub fn line_crossing(p: DVec2, dir: DVec2, a: DVec2, b: DVec2) -> Option<(f64, f64)> {
    let e = b - a;
    let den = dir.perp_dot(e);
    if den.abs() < 1e-12 {
        return None;
    }
    let w = a - p;
    Some((w.perp_dot(e) / den, w.perp_dot(dir) / den))
}

/// True when the segments `a`-`b` and `c`-`d` cross or touch.
fn segments_meet(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let (d1, d2) = (side(c, d, a), side(c, d, b));
    let (d3, d4) = (side(a, b, c), side(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    segment_distance(c, d, a) == 0.0
        || segment_distance(c, d, b) == 0.0
        || segment_distance(a, b, c) == 0.0
        || segment_distance(a, b, d) == 0.0
}

/// The smallest distance between two rings as areas: 0 when they overlap or touch, infinite
/// when either is empty.
pub fn ring_distance(a: &[DVec2], b: &[DVec2]) -> f64 {
    if a.is_empty() || b.is_empty() {
        return f64::INFINITY;
    }
    if contains(a, b[0]) || contains(b, a[0]) {
        return 0.0;
    }
    let (n, m) = (a.len(), b.len());
    let mut best = f64::INFINITY;
    for i in 0..n {
        let (p, q) = (a[i], a[(i + 1) % n]);
        for j in 0..m {
            let (r, t) = (b[j], b[(j + 1) % m]);
            if segments_meet(p, q, r, t) {
                return 0.0;
            }
            best = best
                .min(segment_distance(r, t, p))
                .min(segment_distance(p, q, r));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rect;

    #[test]
    fn segment_distance_to_the_middle_and_past_the_ends() {
        let (a, b) = (DVec2::new(0.0, 0.0), DVec2::new(4.0, 0.0));
        assert_eq!(segment_distance(a, b, DVec2::new(1.0, 3.0)), 3.0);
        assert_eq!(segment_distance(a, b, DVec2::new(7.0, 4.0)), 5.0);
        assert_eq!(segment_distance(a, a, DVec2::new(3.0, 4.0)), 5.0);
    }

    #[test]
    fn a_line_crosses_a_segment_where_it_should() {
        let (a, b) = (DVec2::new(2.0, -1.0), DVec2::new(2.0, 3.0));
        assert_eq!(
            line_crossing(DVec2::ZERO, DVec2::new(0.5, 0.0), a, b),
            Some((4.0, 0.25))
        );
        // Behind the start: t < 0; beyond the segment's end: u > 1.
        assert_eq!(
            line_crossing(DVec2::new(4.0, 5.0), DVec2::X, a, b),
            Some((-2.0, 1.5))
        );
        assert_eq!(line_crossing(DVec2::ZERO, DVec2::Y, a, b), None);
    }

    #[test]
    fn ring_distance_is_zero_for_crossing_rings_and_the_gap_otherwise() {
        // A plus: no vertex of either inside the other, edges cross.
        assert_eq!(
            ring_distance(&rect(-2.0, -0.5, 2.0, 0.5), &rect(-0.5, -2.0, 0.5, 2.0)),
            0.0
        );
        assert_eq!(
            ring_distance(&rect(0.0, 0.0, 4.0, 4.0), &rect(1.0, 1.0, 2.0, 2.0)),
            0.0
        );
        assert!(
            (ring_distance(&rect(0.0, 0.0, 1.0, 1.0), &rect(1.25, 0.5, 2.0, 3.0)) - 0.25).abs()
                < 1e-12
        );
        assert!(
            (ring_distance(&rect(0.0, 0.0, 1.0, 1.0), &rect(2.0, 2.0, 3.0, 3.0)) - 2f64.sqrt())
                .abs()
                < 1e-12
        );
        assert_eq!(ring_distance(&[], &rect(0.0, 0.0, 1.0, 1.0)), f64::INFINITY);
    }
}

//! Plane geometry on rings (closed polygons as point lists, metres): containment, distances,
//! interior points and the frame (width axis, depth axis, extents) of a door's passage.

use glam::DVec2;

/// The axis-aligned rectangle `[x0, x1] x [y0, y1]` as a counter-clockwise ring.
pub fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<DVec2> {
    vec![
        DVec2::new(x0, y0),
        DVec2::new(x1, y0),
        DVec2::new(x1, y1),
        DVec2::new(x0, y1),
    ]
}

/// True when `p` is inside `ring` (even-odd rule; points exactly on an edge may go either way).
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

/// Distance from `p` to the segment `a`-`b`.
pub fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// Distance from `p` to the ring's boundary (0 on the boundary).
pub fn boundary_distance(ring: &[DVec2], p: DVec2) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| segment_distance(p, ring[i], ring[(i + 1) % n]))
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
    segment_distance(a, c, d) == 0.0
        || segment_distance(b, c, d) == 0.0
        || segment_distance(c, a, b) == 0.0
        || segment_distance(d, a, b) == 0.0
}

/// The smallest distance between two rings as areas: 0 when they overlap or touch.
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
                .min(segment_distance(p, r, t))
                .min(segment_distance(r, p, q));
        }
    }
    best
}

/// Signed area (positive when counter-clockwise).
pub fn signed_area(ring: &[DVec2]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| ring[i].perp_dot(ring[(i + 1) % n]))
        .sum::<f64>()
        / 2.0
}

/// Area centroid; the vertex mean for degenerate rings.
pub fn centroid(ring: &[DVec2]) -> Option<DVec2> {
    if ring.is_empty() {
        return None;
    }
    let a = signed_area(ring);
    let n = ring.len();
    if a.abs() < 1e-12 {
        return Some(ring.iter().copied().sum::<DVec2>() / n as f64);
    }
    let mut c = DVec2::ZERO;
    for i in 0..n {
        let (p, q) = (ring[i], ring[(i + 1) % n]);
        c += (p + q) * p.perp_dot(q);
    }
    Some(c / (6.0 * a))
}

/// Bounding box (min, max).
pub fn bounds(ring: &[DVec2]) -> Option<(DVec2, DVec2)> {
    let first = *ring.first()?;
    Some(
        ring.iter()
            .fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))),
    )
}

/// A point inside the ring: its centroid when that is inside, else the middle of the widest
/// horizontal span through the centroid's height (or through the middle of the box).
pub fn interior_point(ring: &[DVec2]) -> Option<DVec2> {
    let c = centroid(ring)?;
    if contains(ring, c) {
        return Some(c);
    }
    let (lo, hi) = bounds(ring)?;
    for y in [
        c.y,
        (lo.y + hi.y) / 2.0,
        lo.y + (hi.y - lo.y) * 0.25,
        lo.y + (hi.y - lo.y) * 0.75,
    ] {
        let mut xs = crossings(ring, y);
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

/// The frame of a passage ring: `axis` along its width (the direction of its longest edge),
/// `normal` across it (the direction of travel), the centre of its extents, and its half
/// width and half depth along those axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassageFrame {
    /// Centre of the ring's extents in the frame.
    pub center: DVec2,
    /// Unit vector along the width.
    pub axis: DVec2,
    /// Unit vector across (axis rotated +90 degrees).
    pub normal: DVec2,
    /// Half the extent along `axis`.
    pub half_width: f64,
    /// Half the extent along `normal`.
    pub half_depth: f64,
}

impl PassageFrame {
    /// The frame of `ring`; `None` for fewer than two distinct points.
    pub fn of(ring: &[DVec2]) -> Option<PassageFrame> {
        let n = ring.len();
        let mut best = (0.0, DVec2::X);
        for i in 0..n {
            let d = ring[(i + 1) % n] - ring[i];
            let len = d.length();
            if len > best.0 + 1e-9 {
                best = (len, d / len);
            }
        }
        if best.0 <= 0.0 {
            return None;
        }
        let mut axis = best.1;
        // A canonical direction, so the same ring gives the same frame whatever its winding.
        if axis.x < -1e-12 || (axis.x.abs() <= 1e-12 && axis.y < 0.0) {
            axis = -axis;
        }
        let normal = axis.perp();
        let (mut u0, mut u1, mut v0, mut v1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in ring {
            let (u, v) = (p.dot(axis), p.dot(normal));
            u0 = u0.min(u);
            u1 = u1.max(u);
            v0 = v0.min(v);
            v1 = v1.max(v);
        }
        let center = axis * ((u0 + u1) / 2.0) + normal * ((v0 + v1) / 2.0);
        Some(PassageFrame {
            center,
            axis,
            normal,
            half_width: (u1 - u0) / 2.0,
            half_depth: (v1 - v0) / 2.0,
        })
    }

    /// The same rectangle with width and depth exchanged (the width axis along the old
    /// normal, in the canonical direction).
    pub fn swapped(&self) -> PassageFrame {
        let mut axis = self.normal;
        if axis.x < -1e-12 || (axis.x.abs() <= 1e-12 && axis.y < 0.0) {
            axis = -axis;
        }
        PassageFrame {
            center: self.center,
            axis,
            normal: axis.perp(),
            half_width: self.half_depth,
            half_depth: self.half_width,
        }
    }

    /// The rectangle `[-hw, hw] x [-hd, hd]` of this frame, counter-clockwise.
    pub fn rectangle(&self, half_width: f64, half_depth: f64) -> Vec<DVec2> {
        let (u, v) = (self.axis * half_width, self.normal * half_depth);
        let c = self.center;
        vec![c - u - v, c + u - v, c + u + v, c - u + v]
    }

    /// The same rectangle shifted along the axis by `offset`.
    pub fn rectangle_at(&self, offset: f64, half_width: f64, half_depth: f64) -> Vec<DVec2> {
        let shifted = PassageFrame {
            center: self.center + self.axis * offset,
            ..*self
        };
        shifted.rectangle(half_width, half_depth)
    }
}

#[cfg(test)]
mod tests {
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
    }

    use super::*;

    fn square() -> Vec<DVec2> {
        vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(0.0, 2.0),
        ]
    }

    #[test]
    fn containment_area_and_centroid() {
        let s = square();
        assert!(contains(&s, DVec2::new(1.0, 1.0)));
        assert!(!contains(&s, DVec2::new(3.0, 1.0)));
        assert_eq!(signed_area(&s), 4.0);
        assert_eq!(centroid(&s), Some(DVec2::new(1.0, 1.0)));
        assert_eq!(area_distance(&s, DVec2::new(3.0, 1.0)), 1.0);
        // An L shape whose centroid is outside: the interior point is inside.
        let l = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(4.0, 0.0),
            DVec2::new(4.0, 0.5),
            DVec2::new(0.5, 0.5),
            DVec2::new(0.5, 4.0),
            DVec2::new(0.0, 4.0),
        ];
        assert!(contains(&l, interior_point(&l).unwrap()));
    }

    #[test]
    fn passage_frame_of_a_rotated_rectangle() {
        let f0 = PassageFrame {
            center: DVec2::new(5.0, 3.0),
            axis: DVec2::from_angle(0.5),
            normal: DVec2::from_angle(0.5).perp(),
            half_width: 0.5,
            half_depth: 0.1,
        };
        let f = PassageFrame::of(&f0.rectangle(0.5, 0.1)).unwrap();
        assert!((f.half_width - 0.5).abs() < 1e-9 && (f.half_depth - 0.1).abs() < 1e-9);
        assert!(f.center.distance(f0.center) < 1e-9);
        assert!(f.axis.dot(f0.axis).abs() > 1.0 - 1e-9);
    }
}

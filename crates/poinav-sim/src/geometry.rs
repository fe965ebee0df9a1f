//! Exact plane geometry in f64 for the simulator: ray casts against segments and oriented boxes,
//! the time of impact of a translating convex polygon against a segment, and overlap (separating
//! axis) tests with the smallest push-out. Plane geometry on rings (containment, distances,
//! centroids) is `poinav-floor`'s `polygon`, ring first.

use glam::DVec2;
use poinav_nav::polygon::boundary_distance;

/// Distance kept between bodies after a stop or a push-out, metres. Keeps touching bodies from
/// counting as overlapping in the next test; far below anything the trace shows (1 µm).
pub const SKIN: f64 = 1e-7;

/// Where the ray `o + t * dir` crosses segment `a`-`b`, as `t >= 0` in units of `dir`
/// (`dir` need not be a unit vector). Parallel segments are never hit: their end points are
/// shared with the neighbouring edges of the same ring, which are.
#[inline]
pub fn ray_segment(o: DVec2, dir: DVec2, a: DVec2, b: DVec2) -> Option<f64> {
    let e = b - a;
    let denom = dir.perp_dot(e);
    if denom.abs() <= 1e-300 {
        return None;
    }
    let ao = a - o;
    let t = ao.perp_dot(e) / denom;
    let u = ao.perp_dot(dir) / denom;
    if t >= 0.0 && (0.0..=1.0).contains(&u) {
        Some(t)
    } else {
        None
    }
}

/// A robot's footprint: a rectangle centred on `c` with its long axis along unit vector `ax`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Obb {
    /// Centre.
    pub c: DVec2,
    /// Unit heading (the `hl` axis).
    pub ax: DVec2,
    /// Half length along the heading.
    pub hl: f64,
    /// Half width across the heading.
    pub hw: f64,
}

impl Obb {
    /// A box at `c` heading `heading` radians.
    pub fn new(c: DVec2, heading: f64, hl: f64, hw: f64) -> Obb {
        Obb {
            c,
            ax: DVec2::from_angle(heading),
            hl,
            hw,
        }
    }

    /// Corners, counter-clockwise, starting front-left.
    #[inline]
    pub fn corners(&self) -> [DVec2; 4] {
        let x = self.ax * self.hl;
        let y = self.ax.perp() * self.hw;
        [
            self.c + x + y,
            self.c - x + y,
            self.c - x - y,
            self.c + x - y,
        ]
    }

    /// Axis-aligned bounds (min, max).
    #[inline]
    pub fn aabb(&self) -> (DVec2, DVec2) {
        let ext = DVec2::new(
            (self.ax.x * self.hl).abs() + (self.ax.y * self.hw).abs(),
            (self.ax.y * self.hl).abs() + (self.ax.x * self.hw).abs(),
        );
        (self.c - ext, self.c + ext)
    }

    /// Radius of the circle around the box.
    pub fn radius(&self) -> f64 {
        self.hl.hypot(self.hw)
    }

    /// Entry distance of the ray `o + t * dir` (unit `dir`) into the box, `None` when it misses
    /// or starts inside.
    #[inline]
    pub fn ray(&self, o: DVec2, dir: DVec2) -> Option<f64> {
        let ay = self.ax.perp();
        let rel = o - self.c;
        let (lo, ld) = (
            DVec2::new(rel.dot(self.ax), rel.dot(ay)),
            DVec2::new(dir.dot(self.ax), dir.dot(ay)),
        );
        let half = DVec2::new(self.hl, self.hw);
        let mut t0 = f64::NEG_INFINITY;
        let mut t1 = f64::INFINITY;
        for k in 0..2 {
            let (p, d, h) = (lo[k], ld[k], half[k]);
            if d.abs() < 1e-300 {
                if p.abs() > h {
                    return None;
                }
            } else {
                let (a, b) = ((-h - p) / d, (h - p) / d);
                let (a, b) = if a < b { (a, b) } else { (b, a) };
                t0 = t0.max(a);
                t1 = t1.min(b);
            }
        }
        (t0 <= t1 && t0 >= 0.0).then_some(t0)
    }

    /// Distance from the centre to the boundary along the direction at `angle` radians from the
    /// heading.
    pub fn extent(&self, angle: f64) -> f64 {
        let (s, c) = angle.sin_cos();
        let along = if c.abs() < 1e-12 {
            f64::INFINITY
        } else {
            self.hl / c.abs()
        };
        let across = if s.abs() < 1e-12 {
            f64::INFINITY
        } else {
            self.hw / s.abs()
        };
        along.min(across)
    }
}

/// The first contact of polygon `poly` (convex, counter-clockwise) translated by `delta`
/// against segment `a`-`b`: the fraction `s` of `delta` travelled and the contact normal
/// (unit, pointing from the segment towards the polygon). Exact for pure translation.
pub fn sweep_segment(poly: &[DVec2; 4], delta: DVec2, a: DVec2, b: DVec2) -> Option<(f64, DVec2)> {
    let mut best: Option<(f64, DVec2)> = None;
    let mut keep = |s: f64, n: DVec2| {
        if s <= 1.0 && best.is_none_or(|(bs, _)| s < bs) {
            best = Some((s, n));
        }
    };
    let e = b - a;
    let len = e.length();
    if len > 0.0 {
        // Corners of the polygon running into the segment.
        let mut n = e.perp() / len;
        if n.dot(delta) > 0.0 {
            n = -n;
        }
        for &p in poly {
            if let Some(s) = ray_segment(p, delta, a, b) {
                keep(s, n);
            }
        }
    }
    // Segment end points running (backwards) into the polygon's edges.
    for k in 0..4 {
        let (p, q) = (poly[k], poly[(k + 1) % 4]);
        let edge = q - p;
        let outward = DVec2::new(edge.y, -edge.x);
        if outward.dot(delta) <= 0.0 {
            continue;
        }
        let n = -outward.normalize();
        for &end in &[a, b] {
            if let Some(s) = ray_segment(end, -delta, p, q) {
                keep(s, n);
            }
        }
    }
    best
}

/// Overlap of polygon `poly` (convex, counter-clockwise) and segment `a`-`b` by the separating
/// axis test: `None` when apart (touching counts as apart), else the smallest push `(depth,
/// unit direction)` that moves the polygon out.
pub fn overlap_segment(poly: &[DVec2; 4], a: DVec2, b: DVec2) -> Option<(f64, DVec2)> {
    let e = b - a;
    let mut axes = [
        (poly[1] - poly[0]).normalize_or_zero(),
        (poly[2] - poly[1]).normalize_or_zero(),
        e.perp().normalize_or_zero(),
    ];
    if axes[2] == DVec2::ZERO {
        axes[2] = axes[0];
    }
    let mut best: Option<(f64, DVec2)> = None;
    for axis in axes {
        let (mut p0, mut p1) = (f64::INFINITY, f64::NEG_INFINITY);
        for &p in poly {
            let d = p.dot(axis);
            p0 = p0.min(d);
            p1 = p1.max(d);
        }
        let (da, db) = (a.dot(axis), b.dot(axis));
        let (s0, s1) = (da.min(db), da.max(db));
        let (up, down) = (s1 - p0, p1 - s0);
        if up <= 0.0 || down <= 0.0 {
            return None;
        }
        let candidate = if up <= down {
            (up, axis)
        } else {
            (down, -axis)
        };
        if best.is_none_or(|(d, _)| candidate.0 < d) {
            best = Some(candidate);
        }
    }
    best
}

/// Smallest distance between two convex polygons given as corner lists (0 when they overlap).
pub fn polygon_gap(p: &[DVec2; 4], q: &[DVec2; 4]) -> f64 {
    for k in 0..4 {
        if overlap_segment(p, q[k], q[(k + 1) % 4]).is_some() {
            return 0.0;
        }
    }
    let mut best = f64::INFINITY;
    for (a, b) in [(p, q), (q, p)] {
        for &v in a.iter() {
            best = best.min(boundary_distance(b, v));
        }
    }
    best
}

/// Wraps an angle to (-pi, pi].
pub fn wrap_angle(a: f64) -> f64 {
    let mut a = a % std::f64::consts::TAU;
    if a > std::f64::consts::PI {
        a -= std::f64::consts::TAU;
    } else if a <= -std::f64::consts::PI {
        a += std::f64::consts::TAU;
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_hit_segments_and_boxes_where_they_should() {
        let o = DVec2::ZERO;
        let t = ray_segment(o, DVec2::X, DVec2::new(2.0, -1.0), DVec2::new(2.0, 1.0));
        assert_eq!(t, Some(2.0));
        assert!(ray_segment(o, -DVec2::X, DVec2::new(2.0, -1.0), DVec2::new(2.0, 1.0)).is_none());
        let b = Obb::new(DVec2::new(3.0, 0.0), 0.0, 0.4, 0.35);
        assert!((b.ray(o, DVec2::X).unwrap() - 2.6).abs() < 1e-12);
        assert!(b.ray(o, DVec2::Y).is_none());
        assert!((b.extent(0.0) - 0.4).abs() < 1e-12);
        assert!((b.extent(std::f64::consts::FRAC_PI_2) - 0.35).abs() < 1e-12);
    }

    #[test]
    fn sweeps_stop_at_first_contact_and_overlaps_push_out() {
        let b = Obb::new(DVec2::ZERO, 0.0, 0.4, 0.35);
        let wall = (DVec2::new(1.0, -2.0), DVec2::new(1.0, 2.0));
        let (s, n) = sweep_segment(&b.corners(), DVec2::new(1.0, 0.0), wall.0, wall.1).unwrap();
        assert!((s - 0.6).abs() < 1e-12);
        assert_eq!(n, DVec2::new(-1.0, 0.0));
        // A thin segment end runs into the box's side.
        let stub = (DVec2::new(0.0, 1.0), DVec2::new(0.0, 3.0));
        let (s, n) = sweep_segment(&b.corners(), DVec2::new(0.0, 1.0), stub.0, stub.1).unwrap();
        assert!((s - 0.65).abs() < 1e-12);
        assert_eq!(n, DVec2::new(0.0, -1.0));
        let moved = Obb::new(DVec2::new(0.7, 0.0), 0.0, 0.4, 0.35);
        let (depth, dir) = overlap_segment(&moved.corners(), wall.0, wall.1).unwrap();
        assert!((depth - 0.1).abs() < 1e-12);
        assert_eq!(dir, DVec2::new(-1.0, 0.0));
        assert!(overlap_segment(&b.corners(), wall.0, wall.1).is_none());
        let other = Obb::new(DVec2::new(2.0, 0.0), 0.0, 0.4, 0.35);
        assert!((polygon_gap(&b.corners(), &other.corners()) - 1.2).abs() < 1e-12);
    }

    #[test]
    fn angles_wrap() {
        assert!((wrap_angle(3.0 * std::f64::consts::PI) - std::f64::consts::PI).abs() < 1e-12);
    }
}

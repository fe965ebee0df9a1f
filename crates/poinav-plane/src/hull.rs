//! Convex hulls (Andrew's monotone chain after an Akl-Toussaint cull) and the minimum-area
//! enclosing rectangle by rotating calipers.

use glam::DVec2;

/// The convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
/// Fewer than three distinct points give those points.
pub fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut pts: Vec<DVec2> = points.iter().copied().filter(|p| p.is_finite()).collect();
    drop_interior(&mut pts);
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// Removes the points strictly inside the quadrilateral of the leftmost, lowest, rightmost
/// and highest points (Akl-Toussaint): none of them is on the hull, and for a dense mesh's
/// vertices they are most, so the sort that follows is short.
fn drop_interior(pts: &mut Vec<DVec2>) {
    if pts.len() < 16 {
        return;
    }
    let pick = |better: fn(DVec2, DVec2) -> bool| {
        pts.iter()
            .copied()
            .reduce(|a, b| if better(b, a) { b } else { a })
    };
    let (Some(l), Some(b), Some(r), Some(t)) = (
        pick(|p, q| p.x < q.x),
        pick(|p, q| p.y < q.y),
        pick(|p, q| p.x > q.x),
        pick(|p, q| p.y > q.y),
    ) else {
        return;
    };
    let quad = [l, b, r, t];
    let inside = |p: DVec2| {
        (0..4).all(|i| {
            let (a, c) = (quad[i], quad[(i + 1) % 4]);
            (c - a).perp_dot(p - a) > 0.0
        })
    };
    pts.retain(|&p| !inside(p));
}

/// A rectangle in the plane: centre, unit direction of its first side, and side lengths.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rectangle {
    /// Its centre.
    pub center: DVec2,
    /// Unit vector along the side of length `length`.
    pub direction: DVec2,
    /// The side along `direction` (the longer one).
    pub length: f64,
    /// The other side (the shorter one).
    pub width: f64,
}

impl Rectangle {
    /// length x width.
    pub fn area(&self) -> f64 {
        self.length * self.width
    }
}

/// The minimum-area rectangle enclosing `points`, by rotating calipers over the edges of their
/// convex hull (one side of the optimum lies on a hull edge). `None` for fewer than two
/// distinct points; collinear points give a rectangle of width 0.
pub fn min_area_rectangle(points: &[DVec2]) -> Option<Rectangle> {
    let hull = convex_hull(points);
    if hull.len() < 2 {
        return None;
    }
    let mut best: Option<(f64, Rectangle)> = None;
    let n = hull.len();
    for i in 0..n {
        let Some(u) = (hull[(i + 1) % n] - hull[i]).try_normalize() else {
            continue;
        };
        let v = u.perp();
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for &p in &hull {
            let q = DVec2::new(p.dot(u), p.dot(v));
            lo = lo.min(q);
            hi = hi.max(q);
        }
        let size = hi - lo;
        let area = size.x * size.y;
        if best.as_ref().is_none_or(|(a, _)| area < *a) {
            let mid = (lo + hi) / 2.0;
            let center = u * mid.x + v * mid.y;
            let rect = if size.x >= size.y {
                Rectangle {
                    center,
                    direction: u,
                    length: size.x,
                    width: size.y,
                }
            } else {
                Rectangle {
                    center,
                    direction: v,
                    length: size.y,
                    width: size.x,
                }
            };
            best = Some((area, rect));
        }
    }
    best.map(|(_, r)| r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::{contains_closed, signed_area};
    use proptest::prelude::*;

    fn rotated_rectangle(l: f64, w: f64, angle_deg: f64, at: DVec2) -> Vec<DVec2> {
        let r = DVec2::from_angle(angle_deg.to_radians());
        [(-l, -w), (l, -w), (l, w), (-l, w)]
            .iter()
            .map(|&(x, y)| at + r.rotate(DVec2::new(x / 2.0, y / 2.0)))
            .collect()
    }

    #[test]
    fn rotating_calipers_on_a_rotated_10_by_2_rectangle() {
        let rect = rotated_rectangle(10.0, 2.0, 30.0, DVec2::new(3.0, -7.0));
        let r = min_area_rectangle(&rect).unwrap();
        assert!((r.length / r.width - 5.0).abs() < 1e-9);
        assert!((r.area() - 20.0).abs() < 1e-9);
        assert!((r.center - DVec2::new(3.0, -7.0)).length() < 1e-9);
        assert!(r.direction.dot(DVec2::from_angle(30f64.to_radians())).abs() > 1.0 - 1e-12);
    }

    #[test]
    fn dense_interiors_leave_the_hull_as_it_is() {
        // 64 points on a circle (some on the extremes' quadrilateral's edges' side), 400 inside.
        let ring: Vec<DVec2> = (0..64)
            .map(|i| DVec2::from_angle(i as f64 * std::f64::consts::TAU / 64.0) * 3.0)
            .collect();
        let mut all = ring.clone();
        for i in 0..20 {
            for j in 0..20 {
                all.push(DVec2::new(i as f64 * 0.2 - 1.9, j as f64 * 0.2 - 1.9));
            }
        }
        all.reverse();
        assert_eq!(convex_hull(&all), convex_hull(&ring));
        assert_eq!(convex_hull(&ring).len(), 64);
    }

    #[test]
    fn hull_drops_interior_and_collinear_points() {
        let pts = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 2.0),
            DVec2::new(0.0, 2.0),
        ];
        let h = convex_hull(&pts);
        assert_eq!(h.len(), 4);
        assert_eq!(signed_area(&h), 4.0);
    }

    proptest! {
        #[test]
        fn calipers_find_any_rectangle(
            l in 0.1f64..100.0, w in 0.1f64..100.0, angle in 0.0f64..360.0,
            x in -1e4f64..1e4, y in -1e4f64..1e4,
        ) {
            let rect = rotated_rectangle(l, w, angle, DVec2::new(x, y));
            let r = min_area_rectangle(&rect).unwrap();
            prop_assert!((r.area() - l * w).abs() <= 1e-6 * l * w);
            prop_assert!((r.length - l.max(w)).abs() <= 1e-6 * l.max(w));
            let hull = convex_hull(&rect);
            prop_assert!((signed_area(&hull) - l * w).abs() <= 1e-6 * l * w);
            prop_assert!(contains_closed(&rect, DVec2::new(x, y)));
        }
    }
}

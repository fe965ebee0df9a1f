//! The surfaces of advanced faces as maps from parameters (u, v) to points in metres, with
//! the inverse for points on them: `IfcPlane`, `IfcCylindricalSurface` (u the angle about
//! the axis, v the height), `IfcSphericalSurface` (longitude, latitude),
//! `IfcToroidalSurface` (angle about the axis, angle about the tube) and B-spline surfaces
//! (rational too, [`crate::bspline`]), `IfcSurfaceOfLinearExtrusion` of a profile's curve
//! (u the length along the curve's polyline, v along the sweep) and `IfcSurfaceOfRevolution`
//! (u the angle, v the length along the curve). Angles (and closed
//! swept curves, and B-spline surfaces along a closed direction) are periodic; normals `S_u x S_v` point away from the axis or centre, as
//! IFC's do.

use std::f64::consts::TAU;

use glam::{DAffine3, DVec2, DVec3};
use poinav_ifc::Entity;

use crate::axis2_placement::axis2placement_3d;
use crate::bspline;
use crate::chord_rule;
use crate::curve::MAX_ARC_STEP;
use crate::error::{degenerate, missing, unsupported, GeomError};
use crate::unit_assignment::Units;

/// A surface an advanced face lies on.
#[derive(Debug, Clone)]
pub enum Surface {
    /// A plane (faces on it are triangulated from their bounds alone).
    Plane,
    /// A cylinder of `radius` about the z axis of `placement`.
    Cylinder {
        /// Local to metres.
        placement: DAffine3,
        /// Radius, metres.
        radius: f64,
    },
    /// A sphere of `radius` about the origin of `placement`.
    Sphere {
        /// Local to metres.
        placement: DAffine3,
        /// Radius, metres.
        radius: f64,
    },
    /// A torus about the z axis of `placement`.
    Torus {
        /// Local to metres.
        placement: DAffine3,
        /// Distance of the tube's centre from the axis, metres.
        major: f64,
        /// The tube's radius, metres.
        minor: f64,
    },
    /// A B-spline surface.
    BSpline(Box<bspline::Surface>),
    /// A curve in the xy plane of `placement` swept along `direction`: u the length along
    /// the curve's polyline, v the distance along `direction`.
    Extrusion(Box<Swept>),
    /// A curve in the xy plane of `placement` turned about the line through the origin
    /// point along `direction` (both in that plane): u the angle, v the length along the
    /// curve; the unit vector is the side of the axis the curve lies on.
    Revolution(Box<(Swept, DVec3, DVec3)>),
}

/// The curve and direction of an `IfcSurfaceOfLinearExtrusion`.
#[derive(Debug, Clone)]
pub struct Swept {
    /// Local to metres.
    pub placement: DAffine3,
    /// The curve's points (metres), as [`crate::curve`] approximates them.
    pub points: Vec<DVec2>,
    /// Length along the points up to each point.
    pub lengths: Vec<f64>,
    /// Unit direction of the sweep (the axis of a revolution), local.
    pub direction: DVec3,
    /// True when the curve closes (u is then periodic).
    pub closed: bool,
}

impl Swept {
    fn total(&self) -> f64 {
        *self.lengths.last().unwrap_or(&0.0)
    }

    /// The curve's point at length `u` (clamped, or wrapped when closed).
    fn at(&self, u: f64) -> DVec2 {
        let total = self.total();
        let u = if self.closed && total > 0.0 {
            u.rem_euclid(total)
        } else {
            u.clamp(0.0, total)
        };
        let i = self
            .lengths
            .partition_point(|&l| l <= u)
            .clamp(1, self.points.len() - 1);
        let (l0, l1) = (self.lengths[i - 1], self.lengths[i]);
        let t = if l1 > l0 { (u - l0) / (l1 - l0) } else { 0.0 };
        self.points[i - 1].lerp(self.points[i], t)
    }

    /// The length along the curve of its point nearest `q`.
    fn length_of(&self, q: DVec2) -> f64 {
        let mut best = (f64::INFINITY, 0.0);
        for i in 1..self.points.len() {
            let (a, b) = (self.points[i - 1], self.points[i]);
            let d = b - a;
            let t = ((q - a).dot(d) / d.length_squared().max(1e-300)).clamp(0.0, 1.0);
            let dist = (a + d * t).distance_squared(q);
            if dist < best.0 {
                best = (
                    dist,
                    self.lengths[i - 1] + t * (self.lengths[i] - self.lengths[i - 1]),
                );
            }
        }
        best.1
    }
}

/// An `IfcSurfaceOfLinearExtrusion` whose `SweptCurve` is an open or closed arbitrary
/// profile bounded by a curve [`crate::curve`] reads.
fn extrusion(e: Entity<'_>, units: &Units) -> Result<Surface, GeomError> {
    let direction = crate::direction::direction(
        e.get_ref("ExtrudedDirection")
            .ok_or_else(|| missing(&e, "ExtrudedDirection"))?,
    )?;
    if direction.z.abs() < 1e-9 {
        return Err(degenerate(&e, "swept along the curve's own plane"));
    }
    Ok(Surface::Extrusion(Box::new(swept_curve(
        e, units, direction,
    )?)))
}

/// An `IfcSurfaceOfRevolution`: its `SweptCurve` (as for extrusions) turned about its
/// `AxisPosition`, which lies in the curve's plane.
fn revolution(e: Entity<'_>, units: &Units) -> Result<Surface, GeomError> {
    let axis = e
        .get_ref("AxisPosition")
        .ok_or_else(|| missing(&e, "AxisPosition"))?;
    let origin = crate::cartesian_point::point3(
        axis.get_ref("Location")
            .ok_or_else(|| missing(&axis, "Location"))?,
    )? * units.metres_per_unit;
    let direction = match axis.get_ref("Axis") {
        Some(d) => crate::direction::direction(d)?,
        None => DVec3::Z,
    };
    if direction.z.abs() > 1e-9 || origin.z.abs() > 1e-9 * origin.length().max(1.0) {
        return Err(unsupported(
            &e,
            "surface of revolution about an axis off the curve's plane",
        ));
    }
    let curve = swept_curve(e, units, direction)?;
    // The side of the axis the curve lies on.
    let side = DVec3::Z.cross(direction);
    let mid = curve.at(curve.total() / 2.0).extend(0.0) - origin;
    let side = if mid.dot(side) < 0.0 { -side } else { side };
    Ok(Surface::Revolution(Box::new((curve, origin, side))))
}

/// The curve of a swept surface's `SweptCurve`, with the surface's placement.
fn swept_curve(e: Entity<'_>, units: &Units, direction: DVec3) -> Result<Swept, GeomError> {
    let s = units.metres_per_unit;
    let profile = e
        .get_ref("SweptCurve")
        .ok_or_else(|| missing(&e, "SweptCurve"))?;
    let curve = profile
        .get_ref("Curve")
        .or_else(|| profile.get_ref("OuterCurve"))
        .ok_or_else(|| unsupported(&profile, "swept curve (an arbitrary profile's curve)"))?;
    let mut points = crate::curve::polyline(curve, units)?;
    let closed = points.len() > 2
        && points[0].distance(points[points.len() - 1]) <= 1e-9 * points[0].length().max(1.0);
    if profile.is_a("IfcArbitraryClosedProfileDef") && !closed {
        points.push(points[0]);
    }
    let closed = closed || profile.is_a("IfcArbitraryClosedProfileDef");
    if points.len() < 2 {
        return Err(degenerate(&e, "swept curve has fewer than two points"));
    }
    let mut lengths = vec![0.0];
    for w in points.windows(2) {
        lengths.push(lengths.last().expect("starts with 0") + w[0].distance(w[1]));
    }
    let placement = match e.get_ref("Position") {
        Some(p) => axis2placement_3d(p, s)?,
        None => DAffine3::IDENTITY,
    };
    Ok(Swept {
        placement,
        points,
        lengths,
        direction,
        closed,
    })
}

/// Reads the `FaceSurface` of an advanced face (of a curve-bounded or trimmed surface, its
/// basis surface).
pub fn surface(e: Entity<'_>, units: &Units) -> Result<Surface, GeomError> {
    // Bounded and trimmed surfaces: the face's own bounds trim it, the basis surface is what
    // counts (followed a few levels at most).
    let mut e = e;
    for _ in 0..4 {
        if !(e.is_a("IfcCurveBoundedPlane")
            || e.is_a("IfcCurveBoundedSurface")
            || e.is_a("IfcRectangularTrimmedSurface"))
        {
            break;
        }
        e = e
            .get_ref("BasisSurface")
            .ok_or_else(|| missing(&e, "BasisSurface"))?;
    }
    let s = units.metres_per_unit;
    let placement = || {
        let p = e
            .get_ref("Position")
            .ok_or_else(|| missing(&e, "Position"))?;
        axis2placement_3d(p, s)
    };
    let length = |name: &'static str| -> Result<f64, GeomError> {
        let v = e.get_f64(name).ok_or_else(|| missing(&e, name))? * s;
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(degenerate(&e, "radius is not a positive number"))
        }
    };
    if e.is_a("IfcPlane") {
        Ok(Surface::Plane)
    } else if e.is_a("IfcCylindricalSurface") {
        Ok(Surface::Cylinder {
            placement: placement()?,
            radius: length("Radius")?,
        })
    } else if e.is_a("IfcSphericalSurface") {
        Ok(Surface::Sphere {
            placement: placement()?,
            radius: length("Radius")?,
        })
    } else if e.is_a("IfcToroidalSurface") {
        Ok(Surface::Torus {
            placement: placement()?,
            major: length("MajorRadius")?,
            minor: length("MinorRadius")?,
        })
    } else if e.is_a("IfcBSplineSurfaceWithKnots") {
        Ok(Surface::BSpline(Box::new(bspline::surface(e, s)?)))
    } else if e.is_a("IfcSurfaceOfLinearExtrusion") {
        extrusion(e, units)
    } else if e.is_a("IfcSurfaceOfRevolution") {
        revolution(e, units)
    } else {
        Err(unsupported(&e, "surface of an advanced face"))
    }
}

impl Surface {
    /// The periods of u and v (`None` when not periodic).
    pub fn periods(&self) -> [Option<f64>; 2] {
        match self {
            Surface::Cylinder { .. } | Surface::Sphere { .. } => [Some(TAU), None],
            Surface::Torus { .. } => [Some(TAU), Some(TAU)],
            Surface::Extrusion(x) if x.closed => [Some(x.total()), None],
            Surface::Revolution(r) if r.0.closed => [Some(TAU), Some(r.0.total())],
            Surface::Revolution(_) => [Some(TAU), None],
            Surface::BSpline(b) => b.periods(),
            Surface::Plane | Surface::Extrusion(_) => [None, None],
        }
    }

    /// Parameter values strictly between `lo` and `hi` at which a face on the surface gets
    /// inner points before it is refined: every [`MAX_ARC_STEP`] of an angle (half a step
    /// off its multiples), the chord
    /// rule's samples of a B-spline's middle iso-curves; none along a cylinder's axis (it is
    /// straight) or on a plane.
    pub fn grid(&self, lo: DVec2, hi: DVec2) -> [Vec<f64>; 2] {
        let angles = |a: f64, b: f64| -> Vec<f64> {
            if (b - a).is_nan() || b - a >= 2.0 * TAU {
                return Vec::new();
            }
            // Half a step off the multiples of the step, where the bounds' arcs have points.
            let first = (a / MAX_ARC_STEP - 0.5).floor() as i64;
            let last = (b / MAX_ARC_STEP - 0.5).ceil() as i64;
            (first..=last)
                .map(|k| (k as f64 + 0.5) * MAX_ARC_STEP)
                .filter(|&x| x > a && x < b)
                .collect()
        };
        match self {
            Surface::Plane | Surface::Extrusion(_) | Surface::Revolution(_) => {
                [Vec::new(), Vec::new()]
            }
            Surface::Cylinder { .. } => [angles(lo.x, hi.x), Vec::new()],
            Surface::Sphere { .. } | Surface::Torus { .. } => {
                [angles(lo.x, hi.x), angles(lo.y, hi.y)]
            }
            Surface::BSpline(b) => {
                let mid = (lo + hi) / 2.0;
                let inside = |ts: Vec<(f64, DVec3)>, a: f64, z: f64| -> Vec<f64> {
                    ts.into_iter()
                        .map(|t| t.0)
                        .filter(|&t| t > a && t < z)
                        .collect()
                };
                let n = |count: usize| (2 * count).min(1024);
                let u = chord_rule::sample(&|u| b.point(u, mid.y), lo.x, hi.x, n(b.u.count()));
                let v = chord_rule::sample(&|v| b.point(mid.x, v), lo.y, hi.y, n(b.v.count()));
                [inside(u, lo.x, hi.x), inside(v, lo.y, hi.y)]
            }
        }
    }

    /// The point at `uv`.
    pub fn point(&self, uv: DVec2) -> DVec3 {
        let (u, v) = (uv.x, uv.y);
        match self {
            Surface::Plane => uv.extend(0.0),
            Surface::Cylinder { placement, radius } => {
                placement.transform_point3(DVec3::new(radius * u.cos(), radius * u.sin(), v))
            }
            Surface::Sphere { placement, radius } => placement.transform_point3(
                DVec3::new(v.cos() * u.cos(), v.cos() * u.sin(), v.sin()) * *radius,
            ),
            Surface::Torus {
                placement,
                major,
                minor,
            } => {
                let rho = major + minor * v.cos();
                placement.transform_point3(DVec3::new(
                    rho * u.cos(),
                    rho * u.sin(),
                    minor * v.sin(),
                ))
            }
            Surface::BSpline(b) => b.point(u, v),
            Surface::Extrusion(x) => x
                .placement
                .transform_point3(x.at(u).extend(0.0) + x.direction * v),
            Surface::Revolution(r) => {
                let (curve, origin, _) = &**r;
                let a = curve.direction;
                let w = curve.at(v).extend(0.0) - *origin;
                let along = a * a.dot(w);
                let perp = w - along;
                let turned = *origin + along + perp * u.cos() + a.cross(perp) * u.sin();
                curve.placement.transform_point3(turned)
            }
        }
    }

    /// Parameters of a point on (or near) the surface; for periodic parameters the value
    /// nearest `near` (when given) modulo the period. `None` where the parameter is not
    /// defined (a sphere's pole: any u).
    pub fn parameters(&self, p: DVec3, near: Option<DVec2>) -> Option<DVec2> {
        let raw = match self {
            Surface::Plane => Some(p.truncate()),
            Surface::Cylinder { placement, .. } => {
                let l = placement.inverse().transform_point3(p);
                Some(DVec2::new(l.y.atan2(l.x), l.z))
            }
            Surface::Sphere { placement, radius } => {
                let l = placement.inverse().transform_point3(p);
                let rho = l.truncate().length();
                if rho < 1e-9 * radius {
                    // At a pole: u comes from the neighbours.
                    let v = if l.z > 0.0 { TAU / 4.0 } else { -TAU / 4.0 };
                    return near.map(|n| DVec2::new(n.x, v));
                }
                Some(DVec2::new(l.y.atan2(l.x), l.z.atan2(rho)))
            }
            Surface::Torus {
                placement, major, ..
            } => {
                let l = placement.inverse().transform_point3(p);
                let rho = l.truncate().length() - major;
                Some(DVec2::new(l.y.atan2(l.x), l.z.atan2(rho)))
            }
            Surface::BSpline(b) => Some(project(b, p, near)),
            Surface::Extrusion(x) => {
                let l = x.placement.inverse().transform_point3(p);
                let v = l.z / x.direction.z;
                Some(DVec2::new(x.length_of((l - x.direction * v).truncate()), v))
            }
            Surface::Revolution(r) => {
                let (curve, origin, side) = &**r;
                let a = curve.direction;
                let w = curve.placement.inverse().transform_point3(p) - *origin;
                let h = a.dot(w);
                let perp = w - a * h;
                let rho = perp.length();
                // The curve's point at the same height and distance from the axis.
                let q = *origin + a * h + *side * rho;
                let u = a.cross(*side).dot(perp).atan2(side.dot(perp));
                Some(DVec2::new(u, curve.length_of(q.truncate())))
            }
        }?;
        let [pu, pv] = self.periods();
        let wrap = |x: f64, period: Option<f64>, n: Option<f64>| match (period, n) {
            (Some(t), Some(n)) => x + ((n - x) / t).round() * t,
            _ => x,
        };
        Some(DVec2::new(
            wrap(raw.x, pu, near.map(|n| n.x)),
            wrap(raw.y, pv, near.map(|n| n.y)),
        ))
    }
}

/// The parameters of the point of `b` nearest `p`: the nearest of a grid (or `near`), then
/// Gauss-Newton steps, kept within the domain (free to cross it where the surface is closed).
fn project(b: &bspline::Surface, p: DVec3, near: Option<DVec2>) -> DVec2 {
    let (u0, u1) = b.u.domain();
    let (v0, v1) = b.v.domain();
    // Along a closed direction the point runs on past the domain's end (modulo the period).
    let [pu, pv] = b.periods();
    let keep = |t: f64, lo: f64, hi: f64, period: Option<f64>| match period {
        Some(_) => t,
        None => t.clamp(lo, hi),
    };
    // Results stay in the domain: wrapped along a closed direction, else clamped.
    let clamp = |x: DVec2| {
        let (u, v) = b.wrap(x.x, x.y);
        DVec2::new(keep(u, u0, u1, pu), keep(v, v0, v1, pv))
    };
    let n = 24;
    let mut best = (f64::INFINITY, DVec2::new(u0, v0));
    let mut consider = |uv: DVec2| {
        let d = b.point(uv.x, uv.y).distance_squared(p);
        if d < best.0 {
            best = (d, uv);
        }
    };
    if let Some(uv) = near {
        consider(clamp(uv));
    }
    for i in 0..=n {
        for j in 0..=n {
            consider(DVec2::new(
                u0 + (u1 - u0) * i as f64 / n as f64,
                v0 + (v1 - v0) * j as f64 / n as f64,
            ));
        }
    }
    let mut uv = best.1;
    let h = 1e-7 * ((u1 - u0) + (v1 - v0));
    for _ in 0..30 {
        let s = b.point(uv.x, uv.y);
        // Central differences, one-sided at the end of a direction that is not closed.
        let (ua, ub) = (keep(uv.x - h, u0, u1, pu), keep(uv.x + h, u0, u1, pu));
        let (va, vb) = (keep(uv.y - h, v0, v1, pv), keep(uv.y + h, v0, v1, pv));
        let du = (b.point(ub, uv.y) - b.point(ua, uv.y)) / (ub - ua);
        let dv = (b.point(uv.x, vb) - b.point(uv.x, va)) / (vb - va);
        let r = p - s;
        let (a, c, d) = (du.dot(du), du.dot(dv), dv.dot(dv));
        let det = a * d - c * c;
        if det.is_nan() || det.abs() <= 1e-300 {
            break;
        }
        let (gu, gv) = (du.dot(r), dv.dot(r));
        // At most half the domain per step: near a collapsed row (a pole) the surface barely
        // moves with one parameter and the plain step runs off.
        let step = DVec2::new(
            ((d * gu - c * gv) / det).clamp(-(u1 - u0) / 2.0, (u1 - u0) / 2.0),
            ((a * gv - c * gu) / det).clamp(-(v1 - v0) / 2.0, (v1 - v0) / 2.0),
        );
        let next = clamp(uv + step);
        if (next - uv).length() < 1e-14 * (1.0 + uv.length()) {
            uv = next;
            break;
        }
        uv = next;
    }
    uv
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_invert_points() {
        let placement =
            DAffine3::from_translation(DVec3::new(1.0, 2.0, 3.0)) * DAffine3::from_rotation_x(0.3);
        let surfaces = [
            Surface::Cylinder {
                placement,
                radius: 0.5,
            },
            Surface::Sphere {
                placement,
                radius: 2.0,
            },
            Surface::Torus {
                placement,
                major: 3.0,
                minor: 1.0,
            },
        ];
        let line = |direction| Swept {
            placement,
            points: vec![
                DVec2::new(1.0, 0.0),
                DVec2::new(1.5, 2.0),
                DVec2::new(1.2, 3.0),
            ],
            lengths: vec![0.0, 4.25f64.sqrt(), 4.25f64.sqrt() + 1.09f64.sqrt()],
            direction,
            closed: false,
        };
        let swept = [
            Surface::Extrusion(Box::new(line(DVec3::new(0.2, 0.0, 1.0).normalize()))),
            Surface::Revolution(Box::new((line(DVec3::Y), DVec3::ZERO, DVec3::X))),
        ];
        for s in &swept {
            for uv in [
                DVec2::new(0.3, 0.2),
                DVec2::new(-2.0, 1.0),
                DVec2::new(2.5, 2.9),
            ] {
                let p = s.point(uv);
                let back = s.parameters(p, Some(uv)).unwrap();
                assert!((s.point(back) - p).length() < 1e-9, "{s:?} {uv} {back}");
            }
        }
        for s in &surfaces {
            for uv in [
                DVec2::new(0.3, 0.2),
                DVec2::new(-2.0, 1.0),
                DVec2::new(3.0, -1.2),
            ] {
                let p = s.point(uv);
                let back = s.parameters(p, Some(uv)).unwrap();
                assert!((back - uv).length() < 1e-9, "{s:?} {uv} {back}");
                // Near a value one period on, the same point gets that period's parameter.
                let shifted = s.parameters(p, Some(uv + DVec2::X * TAU)).unwrap();
                assert!((shifted - uv - DVec2::X * TAU).length() < 1e-9);
            }
        }
    }

    #[test]
    fn a_closed_bowl_with_a_pole_is_periodic_and_projects_within_its_domain() {
        // A bowl: u from a unit circle at z = 1 through one at z = 0 to the pole at the
        // origin (a collapsed row); v round the circles, closed (first column = last).
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let ring = [
            (1.0, 0.0),
            (1.0, 1.0),
            (0.0, 1.0),
            (-1.0, 1.0),
            (-1.0, 0.0),
            (-1.0, -1.0),
            (0.0, -1.0),
            (1.0, -1.0),
            (1.0, 0.0),
        ];
        let weights: Vec<f64> = (0..9).map(|j| if j % 2 == 1 { w } else { 1.0 }).collect();
        let rows: Vec<Vec<DVec3>> = [(1.0, 1.0), (1.0, 0.5), (0.0, 0.0)]
            .iter()
            .map(|&(r, z)| {
                ring.iter()
                    .map(|&(x, y)| DVec3::new(r * x, r * y, z))
                    .collect()
            })
            .collect();
        let knots = |k: &[f64], m: &[i64]| bspline::knot_vector(k, m).unwrap();
        let b = bspline::Surface::new(
            bspline::Basis::new(2, knots(&[0.0, 1.0], &[3, 3]), 3).unwrap(),
            bspline::Basis::new(2, knots(&[0.0, 0.25, 0.5, 0.75, 1.0], &[3, 2, 2, 2, 3]), 9)
                .unwrap(),
            &rows,
            Some(&vec![weights; 3]),
        )
        .unwrap();
        assert_eq!(b.periods(), [None, Some(1.0)]);
        let s = Surface::BSpline(Box::new(b));
        // Past the end of v the surface goes on round.
        assert!((s.point(DVec2::new(0.3, 1.2)) - s.point(DVec2::new(0.3, 0.2))).length() < 1e-12);
        // Points on the surface come back, just before the closing line too.
        for uv in [
            DVec2::new(0.2, 0.99),
            DVec2::new(0.5, 0.01),
            DVec2::new(0.9, 0.6),
        ] {
            let p = s.point(uv);
            let back = s.parameters(p, None).unwrap();
            assert!((s.point(back) - p).length() < 1e-9, "{uv} {back}");
        }
        // Off the surface round the pole, where v barely moves the surface (as the bounds of
        // OpenBuildings' jar): parameters found without v running off.
        for k in 0..24 {
            let a = k as f64 * std::f64::consts::TAU / 24.0;
            let off = DVec3::new(0.15 * a.cos(), 0.15 * a.sin(), 0.0);
            let uv = s.parameters(off, None).unwrap();
            assert!(
                (0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y),
                "{off}: {uv}"
            );
            assert!(s.point(uv).distance(off) < 0.15, "{off}: {uv}");
        }
    }
}

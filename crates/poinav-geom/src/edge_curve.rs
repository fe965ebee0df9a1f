//! `IfcEdgeCurve`: the points of an edge of an advanced brep from its start vertex to its end
//! vertex (both exact) along its `EdgeGeometry`: `IfcLine`, `IfcPolyline`, `IfcCircle` and
//! `IfcEllipse` (arcs by [`MAX_ARC_STEP`]), B-spline curves (rational too, by the chord
//! rule), `IfcIndexedPolyCurve` and `IfcCompositeCurve` (their [`crate::curve3d`] path cut
//! between the vertices), `IfcTrimmedCurve`s of those and surface curves (`IfcSurfaceCurve`,
//! `IfcIntersectionCurve`, `IfcSeamCurve`: their `Curve3D`); `SameSense` false runs against
//! the curve.

use std::f64::consts::TAU;

use glam::DVec3;
use poinav_ifc::Entity;

use crate::axis2_placement::axis2placement;
use crate::bspline;
use crate::cartesian_point::point3;
use crate::curve::MAX_ARC_STEP;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::unit_assignment::Units;

/// Deepest nesting of trimmed curves followed.
const MAX_DEPTH: usize = 8;

/// The point of an `IfcVertexPoint`, metres.
pub fn vertex(v: Entity<'_>, s: f64) -> Result<DVec3, GeomError> {
    let p = required_ref(&v, "VertexGeometry", "IfcCartesianPoint")?;
    Ok(point3(p)? * s)
}

/// The points of an `IfcEdgeCurve` from `EdgeStart` to `EdgeEnd`, metres, ends exact.
pub fn edge_points(edge: Entity<'_>, units: &Units) -> Result<Vec<DVec3>, GeomError> {
    let s = units.metres_per_unit;
    if !edge.is_a("IfcEdgeCurve") {
        return Err(unsupported(&edge, "edge (only IfcEdgeCurve)"));
    }
    let a = vertex(required_ref(&edge, "EdgeStart", "IfcVertex")?, s)?;
    let b = vertex(required_ref(&edge, "EdgeEnd", "IfcVertex")?, s)?;
    let curve = required_ref(&edge, "EdgeGeometry", "IfcCurve")?;
    let sense = edge.get("SameSense").and_then(|v| v.as_enum()) != Some("F");
    let mut pts = between(curve, a, b, sense, units, 0)?;
    if pts.len() < 2 {
        pts = vec![a, b];
    }
    pts[0] = a;
    *pts.last_mut().expect("two points") = b;
    Ok(pts)
}

/// Points of `curve` from near `a` to near `b`, along the curve when `sense`, else against.
fn between(
    curve: Entity<'_>,
    a: DVec3,
    b: DVec3,
    sense: bool,
    units: &Units,
    depth: usize,
) -> Result<Vec<DVec3>, GeomError> {
    let s = units.metres_per_unit;
    if depth > MAX_DEPTH {
        return Err(degenerate(&curve, "curves nested too deeply"));
    }
    let closed = a.distance(b) <= 1e-9 * a.length().max(b.length()).max(1.0);
    if curve.is_a("IfcLine") {
        Ok(vec![a, b])
    } else if curve.is_a("IfcPolyline") {
        let mut pts: Vec<DVec3> = curve
            .get_refs("Points")
            .into_iter()
            .map(|p| point3(p).map(|p| p * s))
            .collect::<Result<_, _>>()?;
        if !sense {
            pts.reverse();
        }
        Ok(pts)
    } else if curve.is_a("IfcCircle") || curve.is_a("IfcEllipse") {
        let position = curve
            .get_ref("Position")
            .ok_or_else(|| missing(&curve, "Position"))?;
        let t = axis2placement(position, s)?;
        let (ra, rb) = if curve.is_a("IfcCircle") {
            let r = curve
                .get_f64("Radius")
                .ok_or_else(|| missing(&curve, "Radius"))?
                * s;
            (r, r)
        } else {
            let a = curve
                .get_f64("SemiAxis1")
                .ok_or_else(|| missing(&curve, "SemiAxis1"))?;
            let b = curve
                .get_f64("SemiAxis2")
                .ok_or_else(|| missing(&curve, "SemiAxis2"))?;
            (a * s, b * s)
        };
        if !(ra > 0.0 && rb > 0.0 && ra.is_finite() && rb.is_finite()) {
            return Err(degenerate(&curve, "radius is not a positive number"));
        }
        let inv = t.inverse();
        let param = |p: DVec3| {
            let l = inv.transform_point3(p);
            (l.y / rb).atan2(l.x / ra)
        };
        let (t0, t1) = (param(a), param(b));
        let sweep = if closed {
            if sense {
                TAU
            } else {
                -TAU
            }
        } else if sense {
            (t1 - t0).rem_euclid(TAU)
        } else {
            -(t0 - t1).rem_euclid(TAU)
        };
        let n = ((sweep.abs() / MAX_ARC_STEP).ceil() as usize).max(1);
        Ok((0..=n)
            .map(|i| {
                let u = t0 + sweep * i as f64 / n as f64;
                t.transform_point3(DVec3::new(ra * u.cos(), rb * u.sin(), 0.0))
            })
            .collect())
    } else if crate::bspline::is_curve(&curve) {
        let c = bspline::curve(curve, s)?;
        let (lo, hi) = c.basis.domain();
        if closed {
            let mut pts = c.sample();
            if !sense {
                pts.reverse();
            }
            return Ok(pts);
        }
        let (ta, tb) = (c.parameter_of(a), c.parameter_of(b));
        let (ta, tb) = if ta == tb { (lo, hi) } else { (ta, tb) };
        Ok(c.sample_between(ta, tb))
    } else if curve.is_a("IfcTrimmedCurve") {
        let basis = required_ref(&curve, "BasisCurve", "IfcCurve")?;
        let agree = curve.get("SenseAgreement").and_then(|v| v.as_enum()) != Some("F");
        between(basis, a, b, sense == agree, units, depth + 1)
    } else if curve.is_a("IfcSurfaceCurve") {
        // Also IfcIntersectionCurve and IfcSeamCurve: the curve in space, as IfcOpenShell
        // reads them (the curves on the surfaces, AssociatedGeometry, are not needed).
        let space = required_ref(&curve, "Curve3D", "IfcCurve")?;
        between(space, a, b, sense, units, depth + 1)
    } else if curve.is_a("IfcIndexedPolyCurve") || curve.is_a("IfcCompositeCurve") {
        // Lines and arcs (3D points, as OpenBuildings writes the edges of a cylinder's caps).
        Ok(crate::curve3d::path(curve, units)?.between(a, b, sense, closed))
    } else {
        Err(unsupported(&curve, "edge curve"))
    }
}

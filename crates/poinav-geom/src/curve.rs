//! `IfcCurve` as a 2D polyline in metres: `IfcPolyline`, `IfcIndexedPolyCurve` (line and arc
//! segments), `IfcCompositeCurve`, `IfcTrimmedCurve` of a circle, ellipse, line or polyline,
//! whole `IfcCircle` / `IfcEllipse` (indexed poly curves, conics and trimmed polylines read by
//! [`crate::curve3d`], z dropped) and B-spline curves ([`crate::bspline`]). Arcs are
//! approximated by chords (see [`MAX_ARC_STEP`]).

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};
use poinav_ifc::{Entity, Value};

use crate::cartesian_point::{point2, point3};
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::unit_assignment::Units;

/// Largest angle one chord of an approximated arc spans (5 degrees: a full circle becomes
/// 72 chords and loses 0.13 % of its area).
pub const MAX_ARC_STEP: f64 = TAU / 72.0;

/// Deepest nesting of composite curves followed.
const MAX_DEPTH: usize = 16;

/// The points of a 3D path in the plane z = 0 (z dropped).
fn flat(path: &crate::curve3d::Path) -> Vec<DVec2> {
    path.points.iter().map(|p| p.truncate()).collect()
}

/// The points of a curve, in order, in metres, in the curve's own 2D coordinates (z dropped).
/// Consecutive duplicate points are removed; a closed curve repeats its first point at the end.
pub fn polyline(curve: Entity<'_>, units: &Units) -> Result<Vec<DVec2>, GeomError> {
    let mut out = Vec::new();
    append(&mut out, &points(curve, units, 0)?);
    Ok(out)
}

/// Appends `more` to `out`, skipping points that repeat the previous one.
fn append(out: &mut Vec<DVec2>, more: &[DVec2]) {
    for &p in more {
        if out
            .last()
            .is_none_or(|q: &DVec2| q.distance(p) > 1e-9 * p.length().max(1.0))
        {
            out.push(p);
        }
    }
}

fn points(curve: Entity<'_>, units: &Units, depth: usize) -> Result<Vec<DVec2>, GeomError> {
    if depth > MAX_DEPTH {
        return Err(degenerate(&curve, "curves nested too deeply"));
    }
    let s = units.metres_per_unit;
    if curve.is_a("IfcPolyline") {
        let pts = curve.get_refs("Points");
        if pts.is_empty() {
            return Err(missing(&curve, "Points"));
        }
        pts.into_iter().map(|p| point2(p).map(|p| p * s)).collect()
    } else if curve.is_a("IfcIndexedPolyCurve") {
        Ok(flat(&crate::curve3d::path(curve, units)?))
    } else if curve.is_a("IfcCompositeCurve") {
        let segments = curve.get_refs("Segments");
        if segments.is_empty() {
            return Err(missing(&curve, "Segments"));
        }
        let mut out = Vec::new();
        for seg in segments {
            let parent = required_ref(&seg, "ParentCurve", "IfcCurve")?;
            let mut pts = points(parent, units, depth + 1)?;
            if seg.get("SameSense").and_then(|v| v.as_enum()) == Some("F") {
                pts.reverse();
            }
            append(&mut out, &pts);
        }
        Ok(out)
    } else if curve.is_a("IfcTrimmedCurve") {
        trimmed_curve(curve, units)
    } else if curve.is_a("IfcCircle") || curve.is_a("IfcEllipse") {
        Ok(flat(&crate::curve3d::path(curve, units)?))
    } else if crate::bspline::is_curve(&curve) {
        let c = crate::bspline::curve(curve, s)?;
        Ok(c.sample().into_iter().map(|p| p.truncate()).collect())
    } else {
        Err(unsupported(&curve, "curve"))
    }
}

/// The arc from `a` through `b` to `c`, approximated by chords; a straight line when the
/// three points are collinear.
pub fn arc_through(a: DVec2, b: DVec2, c: DVec2) -> Vec<DVec2> {
    let d = 2.0 * (a.x * (b.y - c.y) + b.x * (c.y - a.y) + c.x * (a.y - b.y));
    let scale = (b - a).length().max((c - b).length()).max(1e-300);
    if d.abs() < 1e-12 * scale * scale {
        return vec![a, b, c];
    }
    let (a2, b2, c2) = (a.length_squared(), b.length_squared(), c.length_squared());
    let centre = DVec2::new(
        (a2 * (b.y - c.y) + b2 * (c.y - a.y) + c2 * (a.y - b.y)) / d,
        (a2 * (c.x - b.x) + b2 * (a.x - c.x) + c2 * (b.x - a.x)) / d,
    );
    let radius = (a - centre).length();
    let angle = |p: DVec2| (p - centre).to_angle();
    let (t0, t1) = (angle(a), angle(c));
    // Counter-clockwise when a, b, c turn left.
    let ccw = (b - a).perp_dot(c - b) > 0.0;
    let sweep = if ccw {
        (t1 - t0).rem_euclid(TAU)
    } else {
        -(t0 - t1).rem_euclid(TAU)
    };
    let mut out = sample_arc(centre, radius, t0, sweep);
    // Keep the given end points exactly.
    out[0] = a;
    *out.last_mut().expect("an arc has points") = c;
    out
}

/// Points on the circle `centre`, `radius` from angle `t0` over `sweep` (signed) radians,
/// one chord per [`MAX_ARC_STEP`] at most.
pub(crate) fn sample_arc(centre: DVec2, radius: f64, t0: f64, sweep: f64) -> Vec<DVec2> {
    let n = ((sweep.abs() / MAX_ARC_STEP).ceil() as usize).max(1);
    (0..=n)
        .map(|i| centre + radius * DVec2::from_angle(t0 + sweep * i as f64 / n as f64))
        .collect()
}

/// One end of a trimmed curve: a point (metres), a parameter (file units), or both.
#[derive(Default)]
pub(crate) struct Trim {
    pub(crate) point: Option<DVec3>,
    pub(crate) parameter: Option<f64>,
}

/// The `Trim1` or `Trim2` (`attribute`) of the trimmed curve `e`, points scaled by `s`.
pub(crate) fn read_trim(
    e: &Entity<'_>,
    attribute: &'static str,
    s: f64,
) -> Result<Trim, GeomError> {
    let v = e.get(attribute).ok_or_else(|| missing(e, attribute))?;
    let mut trim = Trim::default();
    for item in v.as_list().unwrap_or_default() {
        match item {
            Value::Ref(id) => {
                let p = e.model().entity(*id).ok_or_else(|| missing(e, attribute))?;
                trim.point = Some(point3(p)? * s);
            }
            Value::Typed(_, inner) => trim.parameter = inner.as_f64(),
            _ => {}
        }
    }
    if trim.point.is_none() && trim.parameter.is_none() {
        return Err(missing(e, attribute));
    }
    Ok(trim)
}

/// `IfcTrimmedCurve` on an `IfcCircle`, `IfcEllipse`, `IfcLine` or `IfcPolyline`. Parameters of conics are
/// plane angles in the file's angle unit; the `MasterRepresentation` decides when both a
/// point and a parameter are given.
fn trimmed_curve(curve: Entity<'_>, units: &Units) -> Result<Vec<DVec2>, GeomError> {
    let s = units.metres_per_unit;
    let basis = required_ref(&curve, "BasisCurve", "IfcCurve")?;
    if basis.is_a("IfcCircle") || basis.is_a("IfcEllipse") || basis.is_a("IfcPolyline") {
        // Conics by angle, polylines by point index plus fraction: curve3d reads the trims.
        Ok(flat(&crate::curve3d::path(curve, units)?))
    } else if basis.is_a("IfcLine") {
        let t1 = read_trim(&curve, "Trim1", s)?;
        let t2 = read_trim(&curve, "Trim2", s)?;
        let sense = curve.get("SenseAgreement").and_then(|v| v.as_enum()) != Some("F");
        let prefer_point =
            curve.get("MasterRepresentation").and_then(|v| v.as_enum()) == Some("CARTESIAN");
        let origin = point2(required_ref(&basis, "Pnt", "IfcCartesianPoint")?)? * s;
        let vector = required_ref(&basis, "Dir", "IfcVector")?;
        let dir =
            crate::direction::direction(required_ref(&vector, "Orientation", "IfcDirection")?)?
                .truncate();
        let magnitude = vector.get_f64("Magnitude").unwrap_or(1.0) * s;
        let at = |t: &Trim| match (t.point, t.parameter) {
            (Some(p), Some(_)) if prefer_point => p.truncate(),
            (_, Some(u)) => origin + dir * u * magnitude,
            (Some(p), None) => p.truncate(),
            (None, None) => origin,
        };
        let (a, b) = (at(&t1), at(&t2));
        Ok(if sense { vec![a, b] } else { vec![b, a] })
    } else {
        Err(unsupported(&basis, "basis curve of a trimmed curve"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arc_through_three_points_keeps_ends_and_radius() {
        let pts = arc_through(
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(-1.0, 0.0),
        );
        assert_eq!(pts.len(), 37);
        assert!(pts.iter().all(|p| (p.length() - 1.0).abs() < 1e-12));
        assert!(pts.iter().all(|p| p.y >= -1e-12), "goes over the top");
        let cw = arc_through(
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, -1.0),
            DVec2::new(-1.0, 0.0),
        );
        assert!(cw.iter().all(|p| p.y <= 1e-12), "goes under the bottom");
        let line = arc_through(DVec2::ZERO, DVec2::X, DVec2::X * 2.0);
        assert_eq!(line.len(), 3);
    }
}

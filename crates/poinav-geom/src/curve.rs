//! `IfcCurve` as a 2D polyline in metres: `IfcPolyline`, `IfcIndexedPolyCurve` (line and arc
//! segments), `IfcCompositeCurve`, `IfcTrimmedCurve` of a circle, ellipse or line, and whole
//! `IfcCircle` / `IfcEllipse`, B-spline curves ([`crate::bspline`]). Arcs are approximated by
//! chords (see [`MAX_ARC_STEP`]).

use std::f64::consts::TAU;

use glam::{DAffine2, DVec2};
use poinav_ifc::{Entity, Value};

use crate::axis2_placement::axis2placement;
use crate::cartesian_point::{point2, point_list};
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::unit_assignment::Units;

/// Largest angle one chord of an approximated arc spans (5 degrees: a full circle becomes
/// 72 chords and loses 0.13 % of its area).
pub const MAX_ARC_STEP: f64 = TAU / 72.0;

/// Deepest nesting of composite curves followed.
const MAX_DEPTH: usize = 16;

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
        indexed_poly_curve(curve, s)
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
        let conic = Conic::read(curve, units)?;
        Ok(conic.arc(0.0, TAU))
    } else if curve.is_a("IfcBSplineCurveWithKnots") {
        let c = crate::bspline::curve(curve, s)?;
        Ok(c.sample().into_iter().map(|p| p.truncate()).collect())
    } else {
        Err(unsupported(&curve, "curve"))
    }
}

/// `IfcIndexedPolyCurve`: points from a point list, joined by `IfcLineIndex` and `IfcArcIndex`
/// segments (all points in order when `Segments` is `$`).
fn indexed_poly_curve(curve: Entity<'_>, s: f64) -> Result<Vec<DVec2>, GeomError> {
    let list = required_ref(&curve, "Points", "IfcCartesianPointList")?;
    let pts: Vec<DVec2> = point_list(list)?
        .into_iter()
        .map(|p| p.truncate() * s)
        .collect();
    let Some(segments) = curve.get("Segments") else {
        return Ok(pts);
    };
    let segments = segments
        .as_list()
        .ok_or_else(|| missing(&curve, "Segments"))?;
    let at = |i: &Value<'_>| -> Result<DVec2, GeomError> {
        i.as_i64()
            .and_then(|i| usize::try_from(i).ok())
            .and_then(|i| i.checked_sub(1))
            .and_then(|i| pts.get(i).copied())
            .ok_or_else(|| degenerate(&curve, "segment index outside the point list"))
    };
    let mut out = Vec::new();
    for seg in segments {
        let Value::Typed(kind, inner) = seg else {
            return Err(missing(&curve, "Segments"));
        };
        let idx = inner.as_list().ok_or_else(|| missing(&curve, "Segments"))?;
        let seg_pts: Vec<DVec2> = idx.iter().map(at).collect::<Result<_, _>>()?;
        if kind.eq_ignore_ascii_case("IFCARCINDEX") {
            let [a, b, c] = seg_pts[..] else {
                return Err(degenerate(&curve, "an arc segment needs three indices"));
            };
            append(&mut out, &arc_through(a, b, c));
        } else if kind.eq_ignore_ascii_case("IFCLINEINDEX") {
            append(&mut out, &seg_pts);
        } else {
            return Err(unsupported(&curve, "indexed poly curve segment kind"));
        }
    }
    Ok(out)
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

/// Points on the circle `centre`, `radius` from angle `t0` over `sweep` (signed) radians.
fn sample_arc(centre: DVec2, radius: f64, t0: f64, sweep: f64) -> Vec<DVec2> {
    let n = ((sweep.abs() / MAX_ARC_STEP).ceil() as usize).max(1);
    (0..=n)
        .map(|i| centre + radius * DVec2::from_angle(t0 + sweep * i as f64 / n as f64))
        .collect()
}

/// A circle or ellipse: its placement (metres) and semi-axes (metres).
struct Conic {
    placement: DAffine2,
    a: f64,
    b: f64,
}

impl Conic {
    fn read(e: Entity<'_>, units: &Units) -> Result<Conic, GeomError> {
        let s = units.metres_per_unit;
        let position = e
            .get_ref("Position")
            .ok_or_else(|| missing(&e, "Position"))?;
        let p3 = axis2placement(position, s)?;
        let placement = DAffine2::from_cols(
            p3.matrix3.x_axis.truncate(),
            p3.matrix3.y_axis.truncate(),
            p3.translation.truncate(),
        );
        let (a, b) = if e.is_a("IfcCircle") {
            let r = e.get_f64("Radius").ok_or_else(|| missing(&e, "Radius"))? * s;
            (r, r)
        } else {
            (
                e.get_f64("SemiAxis1")
                    .ok_or_else(|| missing(&e, "SemiAxis1"))?
                    * s,
                e.get_f64("SemiAxis2")
                    .ok_or_else(|| missing(&e, "SemiAxis2"))?
                    * s,
            )
        };
        if !(a > 0.0 && b > 0.0 && a.is_finite() && b.is_finite()) {
            return Err(degenerate(&e, "radius is not a positive number"));
        }
        Ok(Conic { placement, a, b })
    }

    /// Points from parameter `t0` over `sweep` radians (signed).
    fn arc(&self, t0: f64, sweep: f64) -> Vec<DVec2> {
        sample_arc(DVec2::ZERO, 1.0, t0, sweep)
            .into_iter()
            .map(|u| {
                self.placement
                    .transform_point2(DVec2::new(u.x * self.a, u.y * self.b))
            })
            .collect()
    }

    /// The parameter (radians) of a point on or near the conic.
    fn parameter_of(&self, p: DVec2) -> f64 {
        let l = self.placement.inverse().transform_point2(p);
        (l.y / self.b).atan2(l.x / self.a)
    }
}

/// One end of a trimmed curve: a point, a parameter, or both.
#[derive(Default)]
struct Trim {
    point: Option<DVec2>,
    parameter: Option<f64>,
}

fn read_trim(e: &Entity<'_>, attribute: &'static str, s: f64) -> Result<Trim, GeomError> {
    let v = e.get(attribute).ok_or_else(|| missing(e, attribute))?;
    let mut trim = Trim::default();
    for item in v.as_list().unwrap_or_default() {
        match item {
            Value::Ref(id) => {
                let p = e.model().entity(*id).ok_or_else(|| missing(e, attribute))?;
                trim.point = Some(point2(p)? * s);
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

/// `IfcTrimmedCurve` on an `IfcCircle`, `IfcEllipse` or `IfcLine`. Parameters of conics are
/// plane angles in the file's angle unit; the `MasterRepresentation` decides when both a
/// point and a parameter are given.
fn trimmed_curve(curve: Entity<'_>, units: &Units) -> Result<Vec<DVec2>, GeomError> {
    let s = units.metres_per_unit;
    let basis = required_ref(&curve, "BasisCurve", "IfcCurve")?;
    let t1 = read_trim(&curve, "Trim1", s)?;
    let t2 = read_trim(&curve, "Trim2", s)?;
    let sense = curve.get("SenseAgreement").and_then(|v| v.as_enum()) != Some("F");
    let prefer_point =
        curve.get("MasterRepresentation").and_then(|v| v.as_enum()) == Some("CARTESIAN");
    if basis.is_a("IfcCircle") || basis.is_a("IfcEllipse") {
        let conic = Conic::read(basis, units)?;
        let param = |t: &Trim| -> f64 {
            match (t.point, t.parameter) {
                (Some(p), Some(_)) if prefer_point => conic.parameter_of(p),
                (_, Some(u)) => u * units.radians_per_unit,
                (Some(p), None) => conic.parameter_of(p),
                (None, None) => 0.0,
            }
        };
        let (a, b) = (param(&t1), param(&t2));
        let sweep = if sense {
            (b - a).rem_euclid(TAU)
        } else {
            -(a - b).rem_euclid(TAU)
        };
        let sweep = if sweep == 0.0 {
            if sense {
                TAU
            } else {
                -TAU
            }
        } else {
            sweep
        };
        Ok(conic.arc(a, sweep))
    } else if basis.is_a("IfcLine") {
        let origin = point2(required_ref(&basis, "Pnt", "IfcCartesianPoint")?)? * s;
        let vector = required_ref(&basis, "Dir", "IfcVector")?;
        let dir =
            crate::direction::direction(required_ref(&vector, "Orientation", "IfcDirection")?)?
                .truncate();
        let magnitude = vector.get_f64("Magnitude").unwrap_or(1.0) * s;
        let at = |t: &Trim| match (t.point, t.parameter) {
            (Some(p), Some(_)) if prefer_point => p,
            (_, Some(u)) => origin + dir * u * magnitude,
            (Some(p), None) => p,
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

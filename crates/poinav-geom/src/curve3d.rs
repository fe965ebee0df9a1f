//! `IfcCurve` in 3D as a chorded [`Path`] whose points carry the curve's IFC parameter: the
//! directrices of swept solids. Reads `IfcPolyline`, `IfcIndexedPolyCurve` (line and arc
//! segments, 2D or 3D points), `IfcCompositeCurve` (segments with `SameSense`, nested),
//! `IfcTrimmedCurve` of an `IfcCircle`, `IfcEllipse`, `IfcLine` or `IfcPolyline` (trimmed by
//! parameter or by point), whole `IfcCircle` / `IfcEllipse` and B-spline curves (rational
//! too, [`crate::bspline`]), and surface curves by their `Curve3D`; [`Path::trimmed`] cuts a
//! path between two parameters (`StartParam` / `EndParam`). Arcs are chorded by the crate's
//! rule, [`crate::curve::MAX_ARC_STEP`].
//!
//! Parameters follow ISO 10303-42: a polyline's point `i` (from 0) is at `i`; a line's
//! parameter is the distance along it over its vector's magnitude; a conic's is the angle in
//! the file's angle unit; an indexed poly curve counts one per line piece or arc; a trimmed
//! curve keeps its basis curve's; a composite curve adds up the parameter spans of its
//! segments in order; a B-spline curve's is its knots'.

use std::f64::consts::TAU;

use glam::{DAffine3, DVec2, DVec3};
use poinav_ifc::{Entity, Value};

use crate::axis2_placement::axis2placement;
use crate::cartesian_point::{point3, point_list};
use crate::curve::{arc_through, read_trim, sample_arc, Trim};
use crate::direction::direction;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::unit_assignment::Units;

/// Deepest nesting of composite and trimmed curves followed.
const MAX_DEPTH: usize = 16;

/// A curve as points in order (metres), each with the curve's parameter there (file units).
/// Consecutive repeated points are merged; parameters run monotonically (up, or down for a
/// curve traversed against its basis).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Path {
    /// The points, metres.
    pub points: Vec<DVec3>,
    /// The parameter at each point.
    pub params: Vec<f64>,
}

impl Path {
    /// Appends `p` at parameter `u`, unless it repeats the last point.
    fn push(&mut self, p: DVec3, u: f64) {
        if self
            .points
            .last()
            .is_some_and(|q| q.distance(p) <= 1e-9 * p.length().max(1.0))
        {
            return;
        }
        self.points.push(p);
        self.params.push(u);
    }

    fn reverse(&mut self) {
        self.points.reverse();
        self.params.reverse();
    }

    /// Total length, metres.
    pub fn length(&self) -> f64 {
        self.points.windows(2).map(|w| w[0].distance(w[1])).sum()
    }

    /// The part of the path between parameters `start` and `end` (`None`: the path's own
    /// end), in the path's direction; parameters beyond the path's range are clamped to it.
    pub fn trimmed(&self, start: Option<f64>, end: Option<f64>) -> Path {
        let n = self.points.len();
        if n < 2 || (start.is_none() && end.is_none()) {
            return self.clone();
        }
        // Work with keys that increase along the path.
        let sign = if self.params[n - 1] >= self.params[0] {
            1.0
        } else {
            -1.0
        };
        let (k0, k1) = (sign * self.params[0], sign * self.params[n - 1]);
        let key = |u: Option<f64>, default: f64| {
            u.filter(|u| u.is_finite())
                .map_or(default, |u| (sign * u).clamp(k0, k1))
        };
        let (mut a, mut b) = (key(start, k0), key(end, k1));
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        if a <= k0 && b >= k1 {
            return self.clone();
        }
        let mut out = Path::default();
        out.push(self.at_key(a, sign), sign * a);
        for (p, u) in self.points.iter().zip(&self.params) {
            if sign * u > a && sign * u < b {
                out.push(*p, *u);
            }
        }
        out.push(self.at_key(b, sign), sign * b);
        out
    }

    /// The parameter `length` metres along the path from its start (clamped to the path).
    pub fn parameter_at_length(&self, length: f64) -> f64 {
        let mut along = 0.0;
        for i in 0..self.points.len().saturating_sub(1) {
            let d = self.points[i].distance(self.points[i + 1]);
            if along + d >= length && d > 0.0 {
                let f = ((length - along) / d).clamp(0.0, 1.0);
                return self.params[i] + f * (self.params[i + 1] - self.params[i]);
            }
            along += d;
        }
        self.params.last().copied().unwrap_or(0.0)
    }

    /// The points of the path from near `a` to near `b` (ends not snapped): along the path
    /// when `sense`, else against it. `a` and `b` one point (`closed`) gives the whole path
    /// starting and ending at `a`; on a path that closes on itself, a way that would run
    /// backwards goes round through the path's start instead.
    pub fn between(&self, a: DVec3, b: DVec3, sense: bool, closed: bool) -> Vec<DVec3> {
        let n = self.points.len();
        if n < 2 {
            return self.points.clone();
        }
        let ends_meet =
            self.points[0].distance(self.points[n - 1]) <= 1e-9 * self.points[0].length().max(1.0);
        let (ta, tb) = (self.parameter_of(a), self.parameter_of(b));
        let join = |first: Path, second: Path| {
            let mut out = first.points;
            out.extend(second.points.into_iter().skip(1));
            out
        };
        let mut pts = if closed {
            join(self.trimmed(Some(ta), None), self.trimmed(None, Some(ta)))
        } else if (ta <= tb) == sense || !ends_meet {
            self.trimmed(Some(ta), Some(tb)).points
        } else if sense {
            join(self.trimmed(Some(ta), None), self.trimmed(None, Some(tb)))
        } else {
            join(self.trimmed(Some(tb), None), self.trimmed(None, Some(ta)))
        };
        // `trimmed` runs in the path's direction; the edge runs from `a`.
        let backwards = match (closed, pts.first()) {
            (true, _) => !sense,
            (false, Some(p)) => p.distance(b) < p.distance(a),
            (false, None) => false,
        };
        if backwards {
            pts.reverse();
        }
        pts
    }

    /// The point where `sign * parameter` equals `k` (within the path's range).
    fn at_key(&self, k: f64, sign: f64) -> DVec3 {
        for i in 0..self.points.len() - 1 {
            let (u0, u1) = (sign * self.params[i], sign * self.params[i + 1]);
            if k <= u1 || i + 2 == self.points.len() {
                let f = if u1 > u0 {
                    ((k - u0) / (u1 - u0)).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                return self.points[i].lerp(self.points[i + 1], f);
            }
        }
        self.points[0]
    }

    /// The parameter of the point of the path nearest to `p`.
    fn parameter_of(&self, p: DVec3) -> f64 {
        let mut best = (f64::INFINITY, self.params.first().copied().unwrap_or(0.0));
        for i in 0..self.points.len().saturating_sub(1) {
            let (a, b) = (self.points[i], self.points[i + 1]);
            let d = b - a;
            let f = if d.length_squared() > 0.0 {
                ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let dist = p.distance(a + d * f);
            if dist < best.0 {
                best = (
                    dist,
                    self.params[i] + f * (self.params[i + 1] - self.params[i]),
                );
            }
        }
        best.1
    }
}

/// The path of `curve`, metres, with its parameters.
pub fn path(curve: Entity<'_>, units: &Units) -> Result<Path, GeomError> {
    read(curve, units, 0)
}

fn read(curve: Entity<'_>, units: &Units, depth: usize) -> Result<Path, GeomError> {
    if depth > MAX_DEPTH {
        return Err(degenerate(&curve, "curves nested too deeply"));
    }
    let s = units.metres_per_unit;
    let mut out = Path::default();
    if curve.is_a("IfcPolyline") {
        let pts = curve.get_refs("Points");
        if pts.is_empty() {
            return Err(missing(&curve, "Points"));
        }
        for (i, p) in pts.into_iter().enumerate() {
            out.push(point3(p)? * s, i as f64);
        }
    } else if curve.is_a("IfcIndexedPolyCurve") {
        out = indexed_poly_curve(curve, s)?;
    } else if curve.is_a("IfcCompositeCurve") {
        let segments = curve.get_refs("Segments");
        if segments.is_empty() {
            return Err(missing(&curve, "Segments"));
        }
        let mut offset = 0.0;
        for seg in segments {
            if !seg.is_a("IfcCompositeCurveSegment") {
                return Err(unsupported(&seg, "composite curve segment"));
            }
            let parent = required_ref(&seg, "ParentCurve", "IfcCurve")?;
            let mut p = read(parent, units, depth + 1)?;
            if seg.get("SameSense").and_then(|v| v.as_enum()) == Some("F") {
                p.reverse();
            }
            let (Some(&u0), Some(&u1)) = (p.params.first(), p.params.last()) else {
                continue;
            };
            for (q, u) in p.points.iter().zip(&p.params) {
                out.push(*q, offset + (u - u0).abs());
            }
            offset += (u1 - u0).abs();
        }
    } else if curve.is_a("IfcTrimmedCurve") {
        out = trimmed_curve(curve, units, depth)?;
    } else if curve.is_a("IfcCircle") || curve.is_a("IfcEllipse") {
        out = Conic::read(curve, units)?.arc(0.0, TAU, units.radians_per_unit);
    } else if crate::bspline::is_curve(&curve) {
        // Rational ones too; the parameter is the curve's own (its knots' values).
        let c = crate::bspline::curve(curve, s)?;
        let (lo, hi) = c.basis.domain();
        for (u, p) in c.sample_with_parameters(lo, hi) {
            out.push(p, u);
        }
    } else if curve.is_a("IfcSurfaceCurve") {
        // Also IfcIntersectionCurve and IfcSeamCurve: the curve in space, as IfcOpenShell
        // reads them.
        out = read(
            required_ref(&curve, "Curve3D", "IfcCurve")?,
            units,
            depth + 1,
        )?;
    } else {
        return Err(unsupported(&curve, "curve"));
    }
    if out.points.len() < 2 {
        return Err(degenerate(&curve, "curve has no length"));
    }
    Ok(out)
}

/// `IfcIndexedPolyCurve` in 3D: one parameter unit per line piece and per arc.
fn indexed_poly_curve(curve: Entity<'_>, s: f64) -> Result<Path, GeomError> {
    let list = required_ref(&curve, "Points", "IfcCartesianPointList")?;
    let pts: Vec<DVec3> = point_list(list)?.into_iter().map(|p| p * s).collect();
    let mut out = Path::default();
    let Some(segments) = curve.get("Segments") else {
        for (i, p) in pts.into_iter().enumerate() {
            out.push(p, i as f64);
        }
        return Ok(out);
    };
    let segments = segments
        .as_list()
        .ok_or_else(|| missing(&curve, "Segments"))?;
    let at = |i: &Value<'_>| -> Result<DVec3, GeomError> {
        i.as_i64()
            .and_then(|i| usize::try_from(i).ok())
            .and_then(|i| i.checked_sub(1))
            .and_then(|i| pts.get(i).copied())
            .ok_or_else(|| degenerate(&curve, "segment index outside the point list"))
    };
    let mut u = 0.0;
    for seg in segments {
        let Value::Typed(kind, inner) = seg else {
            return Err(missing(&curve, "Segments"));
        };
        let idx = inner.as_list().ok_or_else(|| missing(&curve, "Segments"))?;
        let seg_pts: Vec<DVec3> = idx.iter().map(at).collect::<Result<_, _>>()?;
        if kind.eq_ignore_ascii_case("IFCARCINDEX") {
            let [a, b, c] = seg_pts[..] else {
                return Err(degenerate(&curve, "an arc segment needs three indices"));
            };
            let arc = arc_through_3d(a, b, c);
            let n = (arc.len() - 1) as f64;
            for (i, p) in arc.into_iter().enumerate() {
                out.push(p, u + i as f64 / n);
            }
            u += 1.0;
        } else if kind.eq_ignore_ascii_case("IFCLINEINDEX") {
            for (i, p) in seg_pts.into_iter().enumerate() {
                if i > 0 {
                    u += 1.0;
                }
                out.push(p, u);
            }
        } else {
            return Err(unsupported(&curve, "indexed poly curve segment kind"));
        }
    }
    Ok(out)
}

/// The arc from `a` through `b` to `c` in their plane, chorded as [`arc_through`] does; a
/// straight line when the three points are collinear.
pub fn arc_through_3d(a: DVec3, b: DVec3, c: DVec3) -> Vec<DVec3> {
    let normal = (b - a).cross(c - a);
    let scale = (b - a).length_squared().max((c - a).length_squared());
    let (Some(x), true) = ((b - a).try_normalize(), normal.length() > 1e-12 * scale) else {
        return vec![a, b, c];
    };
    let y = normal.normalize().cross(x);
    let flat = |p: DVec3| DVec2::new((p - a).dot(x), (p - a).dot(y));
    let mut out: Vec<DVec3> = arc_through(flat(a), flat(b), flat(c))
        .into_iter()
        .map(|q| a + x * q.x + y * q.y)
        .collect();
    out[0] = a;
    *out.last_mut().expect("an arc has points") = c;
    out
}

/// A circle or ellipse in 3D: its placement (metres) and semi-axes (metres).
struct Conic {
    placement: DAffine3,
    a: f64,
    b: f64,
}

impl Conic {
    fn read(e: Entity<'_>, units: &Units) -> Result<Conic, GeomError> {
        let s = units.metres_per_unit;
        let position = e
            .get_ref("Position")
            .ok_or_else(|| missing(&e, "Position"))?;
        let placement = axis2placement(position, s)?;
        let length = |name: &'static str| -> Result<f64, GeomError> {
            Ok(e.get_f64(name).ok_or_else(|| missing(&e, name))? * s)
        };
        let (a, b) = if e.is_a("IfcCircle") {
            let r = length("Radius")?;
            (r, r)
        } else {
            (length("SemiAxis1")?, length("SemiAxis2")?)
        };
        if !(a > 0.0 && b > 0.0 && a.is_finite() && b.is_finite()) {
            return Err(degenerate(&e, "radius is not a positive number"));
        }
        Ok(Conic { placement, a, b })
    }

    /// Points from angle `t0` over `sweep` radians (signed), parameters in the file's angle
    /// unit (`radians_per_unit`).
    fn arc(&self, t0: f64, sweep: f64, radians_per_unit: f64) -> Path {
        let pts = sample_arc(DVec2::ZERO, 1.0, t0, sweep);
        let n = (pts.len() - 1) as f64;
        let mut out = Path::default();
        for (i, u) in pts.into_iter().enumerate() {
            let p = self
                .placement
                .transform_point3(DVec3::new(u.x * self.a, u.y * self.b, 0.0));
            out.push(p, (t0 + sweep * i as f64 / n) / radians_per_unit);
        }
        out
    }

    /// The angle (radians) of a point on or near the conic.
    fn angle_of(&self, p: DVec3) -> f64 {
        let l = self.placement.inverse().transform_point3(p);
        (l.y / self.b).atan2(l.x / self.a)
    }
}

/// `IfcTrimmedCurve` in 3D. The `MasterRepresentation` decides when both a point and a
/// parameter are given; `SenseAgreement` picks the way round a conic.
fn trimmed_curve(curve: Entity<'_>, units: &Units, depth: usize) -> Result<Path, GeomError> {
    let s = units.metres_per_unit;
    let basis = required_ref(&curve, "BasisCurve", "IfcCurve")?;
    let t1 = read_trim(&curve, "Trim1", s)?;
    let t2 = read_trim(&curve, "Trim2", s)?;
    let sense = curve.get("SenseAgreement").and_then(|v| v.as_enum()) != Some("F");
    let prefer_point =
        curve.get("MasterRepresentation").and_then(|v| v.as_enum()) == Some("CARTESIAN");
    // The parameter of a trim: `of_point` maps a point to a parameter, `of_value` a value.
    let param = |t: &Trim, of_point: &dyn Fn(DVec3) -> f64, of_value: &dyn Fn(f64) -> f64| match (
        t.point,
        t.parameter,
    ) {
        (Some(p), Some(_)) if prefer_point => of_point(p),
        (_, Some(u)) => of_value(u),
        (Some(p), None) => of_point(p),
        (None, None) => 0.0,
    };
    if basis.is_a("IfcCircle") || basis.is_a("IfcEllipse") {
        let conic = Conic::read(basis, units)?;
        let rpu = units.radians_per_unit;
        let of_point = |p: DVec3| conic.angle_of(p);
        let of_value = |u: f64| u * rpu;
        let (a, b) = (
            param(&t1, &of_point, &of_value),
            param(&t2, &of_point, &of_value),
        );
        let sweep = if sense {
            (b - a).rem_euclid(TAU)
        } else {
            -(a - b).rem_euclid(TAU)
        };
        let sweep = match (sweep.abs() < 1e-12, sense) {
            (true, true) => TAU,
            (true, false) => -TAU,
            (false, _) => sweep,
        };
        Ok(conic.arc(a, sweep, rpu))
    } else if basis.is_a("IfcLine") {
        let origin = point3(required_ref(&basis, "Pnt", "IfcCartesianPoint")?)? * s;
        let vector = required_ref(&basis, "Dir", "IfcVector")?;
        let dir = direction(required_ref(&vector, "Orientation", "IfcDirection")?)?;
        let magnitude = vector.get_f64("Magnitude").unwrap_or(1.0) * s;
        if !(magnitude.is_finite() && magnitude > 0.0) {
            return Err(degenerate(&vector, "Magnitude is not a positive number"));
        }
        let of_point = |p: DVec3| (p - origin).dot(dir) / magnitude;
        let of_value = |u: f64| u;
        let mut out = Path::default();
        for t in [&t1, &t2] {
            let u = param(t, &of_point, &of_value);
            out.push(origin + dir * u * magnitude, u);
        }
        Ok(out)
    } else if basis.is_a("IfcPolyline") {
        let whole = read(basis, units, depth + 1)?;
        let of_point = |p: DVec3| whole.parameter_of(p);
        let of_value = |u: f64| u;
        let (a, b) = (
            param(&t1, &of_point, &of_value),
            param(&t2, &of_point, &of_value),
        );
        let mut out = whole.trimmed(Some(a.min(b)), Some(a.max(b)));
        if a > b {
            out.reverse();
        }
        Ok(out)
    } else {
        Err(unsupported(&basis, "basis curve of a trimmed curve"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_ifc::{EntityId, Model};

    fn model(data: &str) -> Model {
        crate::test_model::ifc4(data)
    }

    #[test]
    fn polyline_parameters_and_trims() {
        let m = model(
            "#1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCCARTESIANPOINT((2.,0.,0.));\
             #3=IFCCARTESIANPOINT((2.,4.,1.));#4=IFCPOLYLINE((#1,#2,#3));\
             #5=IFCTRIMMEDCURVE(#4,(IFCPARAMETERVALUE(0.5)),(#3),.T.,.PARAMETER.);",
        );
        let p = path(m.entity(EntityId(4)).unwrap(), &Units::SI).unwrap();
        assert_eq!(p.params, vec![0.0, 1.0, 2.0]);
        let t = p.trimmed(Some(0.25), Some(1.5));
        assert_eq!(t.points.len(), 3);
        assert!((t.points[0] - DVec3::new(0.5, 0.0, 0.0)).length() < 1e-12);
        assert!((t.points[2] - DVec3::new(2.0, 2.0, 0.5)).length() < 1e-12);
        assert!((p.parameter_at_length(2.5) - (1.0 + 0.5 / 17f64.sqrt())).abs() < 1e-12);
        assert_eq!(p.parameter_at_length(-1.0), 0.0);
        assert_eq!(p.parameter_at_length(99.0), 2.0);
        // Out-of-range parameters are clamped: the whole path.
        assert_eq!(p.trimmed(Some(-1.0), Some(9.0)), p);
        let tc = path(m.entity(EntityId(5)).unwrap(), &Units::SI).unwrap();
        assert!((tc.points[0] - DVec3::new(1.0, 0.0, 0.0)).length() < 1e-12);
        assert!(
            (tc.points
                .last()
                .unwrap()
                .distance(DVec3::new(2.0, 4.0, 1.0)))
                < 1e-12
        );
        assert!((tc.length() - (1.0 + 17f64.sqrt())).abs() < 1e-12);
    }

    #[test]
    fn between_two_points_of_a_closed_square_goes_the_edges_way() {
        // The unit square (0,0) (1,0) (1,1) (0,1) and back to its start.
        let m = model(
            "#1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCCARTESIANPOINT((1.,0.,0.));\
             #3=IFCCARTESIANPOINT((1.,1.,0.));#4=IFCCARTESIANPOINT((0.,1.,0.));\
             #5=IFCPOLYLINE((#1,#2,#3,#4,#1));",
        );
        let p = path(m.entity(EntityId(5)).unwrap(), &Units::SI).unwrap();
        let (a, b) = (DVec3::new(0.5, 0.0, 0.0), DVec3::new(0.5, 1.0, 0.0));
        let v = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        // Along the curve: by (1,0) and (1,1); against it: by (0,0) and (0,1), back round
        // through the curve's start.
        assert_eq!(
            p.between(a, b, true, false),
            vec![a, v(1., 0.), v(1., 1.), b]
        );
        assert_eq!(
            p.between(a, b, false, false),
            vec![a, v(0., 0.), v(0., 1.), b]
        );
        assert_eq!(
            p.between(b, a, true, false),
            vec![b, v(0., 1.), v(0., 0.), a]
        );
        // One vertex: the whole square from it, each way.
        let c = v(1.0, 0.5);
        let round = vec![c, v(1., 1.), v(0., 1.), v(0., 0.), v(1., 0.), c];
        assert_eq!(p.between(c, c, true, true), round);
        let back: Vec<DVec3> = round.iter().rev().copied().collect();
        assert_eq!(p.between(c, c, false, true), back);
    }

    #[test]
    fn composite_of_line_and_quarter_circle_in_3d() {
        // A line up the y axis at x = 1, then a quarter circle of radius 1 in the plane z = 2
        // turning towards -x; parameters: 0..1 on the polyline, then 0..90 degrees.
        let m = model(
            "#1=IFCCARTESIANPOINT((1.,-3.,2.));#2=IFCCARTESIANPOINT((1.,0.,2.));\
             #3=IFCPOLYLINE((#1,#2));#4=IFCCARTESIANPOINT((0.,0.,2.));\
             #5=IFCAXIS2PLACEMENT3D(#4,$,$);#6=IFCCIRCLE(#5,1.);\
             #7=IFCTRIMMEDCURVE(#6,(IFCPARAMETERVALUE(0.)),(IFCPARAMETERVALUE(90.)),.T.,.PARAMETER.);\
             #8=IFCCOMPOSITECURVESEGMENT(.CONTINUOUS.,.T.,#3);\
             #9=IFCCOMPOSITECURVESEGMENT(.CONTINUOUS.,.T.,#7);#10=IFCCOMPOSITECURVE((#8,#9),.F.);",
        );
        let degrees = Units {
            metres_per_unit: 1.0,
            radians_per_unit: std::f64::consts::PI / 180.0,
        };
        let p = path(m.entity(EntityId(10)).unwrap(), &degrees).unwrap();
        assert_eq!(p.points.len(), 2 + 18);
        assert!((p.params.last().unwrap() - 91.0).abs() < 1e-9);
        assert!((p.points.last().unwrap().distance(DVec3::new(0.0, 1.0, 2.0))) < 1e-12);
        let chords = 18.0 * 2.0 * (std::f64::consts::PI / 72.0).sin();
        assert!((p.length() - (3.0 + chords)).abs() < 1e-9);
        // Trimmed at the middle of the arc (parameter 1 + 45 degrees).
        let t = p.trimmed(Some(0.5), Some(46.0));
        let end = *t.points.last().unwrap();
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!(end.distance(DVec3::new(h, h, 2.0)) < 1e-12, "{end}");
    }

    #[test]
    fn a_rational_b_spline_directrix_is_a_quarter_circle_with_its_knot_parameters() {
        // Degree 2, weights 1, sqrt(1/2), 1: the quarter circle of radius 2 from (2,0,1) to
        // (0,2,1); knots 0 and 3 with multiplicity 3.
        let m = model(
            "#1=IFCCARTESIANPOINT((2.,0.,1.));#2=IFCCARTESIANPOINT((2.,2.,1.));\
             #3=IFCCARTESIANPOINT((0.,2.,1.));\
             #4=IFCRATIONALBSPLINECURVEWITHKNOTS(2,(#1,#2,#3),.CIRCULAR_ARC.,.F.,.F.,(3,3),\
             (0.,3.),.UNSPECIFIED.,(1.,0.7071067811865476,1.));",
        );
        let p = path(m.entity(EntityId(4)).unwrap(), &Units::SI).unwrap();
        assert!(p.points.len() >= 18, "{} points", p.points.len());
        for q in &p.points {
            assert!((q.truncate().length() - 2.0).abs() < 1e-9, "{q}");
            assert!((q.z - 1.0).abs() < 1e-12);
        }
        assert_eq!(p.params.first(), Some(&0.0));
        assert_eq!(p.params.last(), Some(&3.0));
        assert!(p.params.windows(2).all(|w| w[1] > w[0]));
        let t = p.trimmed(Some(0.0), Some(1.5));
        assert!((t.points.last().unwrap().truncate() - DVec2::splat(2f64.sqrt())).length() < 5e-3);
    }

    #[test]
    fn arc_through_3d_stays_on_its_circle() {
        let (a, b, c) = (
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 0.5f64.sqrt(), 0.5f64.sqrt()),
            DVec3::new(-1.0, 0.0, 0.0),
        );
        let arc = arc_through_3d(a, b, c);
        // The circle through them: centre (0, 0, 0), radius 1, in the plane y = z.
        assert!(arc.iter().all(|p| (p.length() - 1.0).abs() < 1e-12));
        assert!(arc
            .iter()
            .all(|p| (p.y - p.z).abs() < 1e-12 && p.y >= -1e-12));
        assert_eq!(arc.len(), 37);
    }
}

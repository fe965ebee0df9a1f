//! B-spline curves and surfaces (`IfcBSplineCurveWithKnots`, `IfcBSplineSurfaceWithKnots` and
//! their rational subtypes; IFC2X3's `IfcBezierCurve` and `IfcRationalBezierCurve`, whose
//! knots are implied: Bezier pieces of its degree end to end): knot vectors from knots and
//! multiplicities, basis functions by
//! the Cox-de Boor recursion, points from homogeneous control points (weights; a surface
//! closed along u or v repeats with its domain's length as period), and the
//! curve's points sampled by the chord rule ([`crate::chord_rule`]).

use glam::{DVec3, DVec4};
use poinav_ifc::{Entity, Value};

use crate::cartesian_point::point3;
use crate::chord_rule;
use crate::error::{degenerate, missing, GeomError};

/// Highest degree accepted (IFC files use 1 to 3, rarely up to 9).
pub const MAX_DEGREE: usize = 25;

/// Most control points one curve or surface may have.
pub const MAX_CONTROL_POINTS: usize = 1 << 20;

/// The full knot vector from distinct `knots` each repeated by its multiplicity; `None` when
/// the lists differ in length, a multiplicity is not positive or knots decrease.
pub fn knot_vector(knots: &[f64], multiplicities: &[i64]) -> Option<Vec<f64>> {
    if knots.len() != multiplicities.len() || knots.is_empty() {
        return None;
    }
    let mut out = Vec::new();
    for (&k, &m) in knots.iter().zip(multiplicities) {
        if !(1..=MAX_DEGREE as i64 + 1).contains(&m) || !k.is_finite() {
            return None;
        }
        if out.last().is_some_and(|&l: &f64| l > k) {
            return None;
        }
        out.extend(std::iter::repeat_n(k, m as usize));
    }
    Some(out)
}

/// A knot vector with its degree: the span of a parameter and the basis functions there.
#[derive(Debug, Clone, PartialEq)]
pub struct Basis {
    /// Degree p.
    pub degree: usize,
    /// The full knot vector (n + p + 1 knots for n control points).
    pub knots: Vec<f64>,
}

impl Basis {
    /// A basis for `count` control points; `None` when the knot vector's length is not
    /// `count + degree + 1` or its domain is empty.
    pub fn new(degree: usize, knots: Vec<f64>, count: usize) -> Option<Basis> {
        if degree == 0 || degree > MAX_DEGREE || count <= degree {
            return None;
        }
        if knots.len() != count + degree + 1 {
            return None;
        }
        let b = Basis { degree, knots };
        let (lo, hi) = b.domain();
        (hi > lo).then_some(b)
    }

    /// Number of control points.
    pub fn count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The parameter domain `[u_p, u_n]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.count()])
    }

    /// The distinct knots inside the domain, ends included (where the curve may bend).
    pub fn breaks(&self) -> Vec<f64> {
        let (lo, hi) = self.domain();
        let mut out: Vec<f64> = Vec::new();
        for &k in &self.knots[self.degree..=self.count()] {
            if (lo..=hi).contains(&k) && out.last() != Some(&k) {
                out.push(k);
            }
        }
        out
    }

    /// The index `i` of the knot span `[u_i, u_{i+1})` holding `t` (clamped to the domain).
    pub fn span(&self, t: f64) -> usize {
        let n = self.count();
        let (lo, hi) = self.domain();
        if t >= hi {
            // The last non-empty span.
            let mut i = n - 1;
            while i > self.degree && self.knots[i] >= self.knots[i + 1] {
                i -= 1;
            }
            return i;
        }
        let t = t.max(lo);
        // Largest i in [p, n - 1] with u_i <= t.
        let (mut a, mut b) = (self.degree, n);
        while b - a > 1 {
            let m = (a + b) / 2;
            if self.knots[m] <= t {
                a = m;
            } else {
                b = m;
            }
        }
        a
    }

    /// The p + 1 basis functions not zero on `span` at `t`: `N_{span-p..=span, p}(t)`.
    pub fn functions(&self, span: usize, t: f64) -> Vec<f64> {
        let p = self.degree;
        let u = &self.knots;
        let mut n = vec![0.0; p + 1];
        let mut left = vec![0.0; p + 1];
        let mut right = vec![0.0; p + 1];
        n[0] = 1.0;
        for j in 1..=p {
            left[j] = t - u[span + 1 - j];
            right[j] = u[span + j] - t;
            let mut saved = 0.0;
            for r in 0..j {
                let den = right[r + 1] + left[j - r];
                let tmp = if den != 0.0 { n[r] / den } else { 0.0 };
                n[r] = saved + right[r + 1] * tmp;
                saved = left[j - r] * tmp;
            }
            n[j] = saved;
        }
        n
    }
}

/// Homogeneous control points `(w x, w y, w z, w)`; `None` when a weight is not positive.
fn homogeneous(points: &[DVec3], weights: Option<&[f64]>) -> Option<Vec<DVec4>> {
    points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let w = weights.map_or(Some(1.0), |w| w.get(i).copied())?;
            (w.is_finite() && w > 0.0).then(|| (*p * w).extend(w))
        })
        .collect()
}

/// A (possibly rational) B-spline curve in 3D.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// The basis.
    pub basis: Basis,
    points: Vec<DVec4>,
}

impl Curve {
    /// A curve of `degree` through `points` (with `weights` when rational) on the knot vector
    /// `knots`; `None` when they do not fit together.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        points: &[DVec3],
        weights: Option<&[f64]>,
    ) -> Option<Curve> {
        let basis = Basis::new(degree, knots, points.len())?;
        Some(Curve {
            basis,
            points: homogeneous(points, weights)?,
        })
    }

    /// The point at parameter `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        let span = self.basis.span(t);
        let n = self.basis.functions(span, t);
        let p = self.basis.degree;
        let h: DVec4 = (0..=p).map(|i| self.points[span - p + i] * n[i]).sum();
        h.truncate() / h.w
    }

    /// Points along the whole curve, cut by the chord rule (each knot span first in
    /// `degree + 1` pieces), first and last control points' ends included.
    pub fn sample(&self) -> Vec<DVec3> {
        let (lo, hi) = self.basis.domain();
        self.sample_between(lo, hi)
    }

    /// Points from parameter `t0` to `t1` (either order), cut by the chord rule.
    pub fn sample_between(&self, t0: f64, t1: f64) -> Vec<DVec3> {
        self.sample_with_parameters(t0, t1)
            .into_iter()
            .map(|(_, p)| p)
            .collect()
    }

    /// Points from parameter `t0` to `t1` (either order), cut by the chord rule, each with
    /// its parameter.
    pub fn sample_with_parameters(&self, t0: f64, t1: f64) -> Vec<(f64, DVec3)> {
        let breaks = self.basis.breaks();
        let (a, b) = (t0.min(t1), t0.max(t1));
        let mut cuts = vec![a];
        cuts.extend(breaks.iter().copied().filter(|&k| k > a && k < b));
        cuts.push(b);
        let mut out = vec![(a, self.point(a))];
        for w in cuts.windows(2) {
            let pts = chord_rule::sample(&|t| self.point(t), w[0], w[1], self.basis.degree + 1);
            out.extend(pts.into_iter().skip(1));
        }
        if t1 < t0 {
            out.reverse();
        }
        out
    }

    /// The parameter of the curve's point nearest `p` (a dense scan, then bisection).
    pub fn parameter_of(&self, p: DVec3) -> f64 {
        let (lo, hi) = self.basis.domain();
        let n = (16 * self.basis.count()).min(4096);
        let at = |i: usize| lo + (hi - lo) * i as f64 / n as f64;
        let best = (0..=n)
            .min_by(|&a, &b| {
                let d = |i| self.point(at(i)).distance_squared(p);
                d(a).total_cmp(&d(b))
            })
            .unwrap_or(0);
        let (mut a, mut b) = (at(best.saturating_sub(1)), at((best + 1).min(n)));
        for _ in 0..60 {
            let (m1, m2) = (a + (b - a) / 3.0, b - (b - a) / 3.0);
            if self.point(m1).distance_squared(p) <= self.point(m2).distance_squared(p) {
                b = m2;
            } else {
                a = m1;
            }
        }
        (a + b) / 2.0
    }
}

/// A (possibly rational) B-spline surface in 3D; control points row by row in u.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// The basis along u (first index of the control points).
    pub u: Basis,
    /// The basis along v.
    pub v: Basis,
    points: Vec<Vec<DVec4>>,
    /// Whether the surface closes on itself along u and along v: its first and last rows
    /// (columns) of control points are the same points (OpenBuildings' cylinders), or the
    /// file says so (`UClosed`, `VClosed`, [`Surface::closed`]); then it repeats with its
    /// domain's length as period.
    closed: [bool; 2],
}

impl Surface {
    /// A surface from its bases and `points[i][j]` (i along u), `weights` likewise.
    pub fn new(
        u: Basis,
        v: Basis,
        points: &[Vec<DVec3>],
        weights: Option<&[Vec<f64>]>,
    ) -> Option<Surface> {
        if points.len() != u.count() || points.iter().any(|r| r.len() != v.count()) {
            return None;
        }
        let rows = points
            .iter()
            .enumerate()
            .map(|(i, row)| {
                homogeneous(
                    row,
                    weights.map(|w| w.get(i).map(|r| &r[..]).unwrap_or(&[])),
                )
            })
            .collect::<Option<Vec<_>>>()?;
        let size = points
            .iter()
            .flatten()
            .fold(0.0f64, |m, p| m.max((*p - points[0][0]).length()))
            .max(1e-9);
        let same =
            |a: &[DVec3], b: &[DVec3]| a.iter().zip(b).all(|(p, q)| p.distance(*q) <= 1e-9 * size);
        let closed_u = points.len() > 2 && same(&points[0], &points[points.len() - 1]);
        let first: Vec<DVec3> = points.iter().map(|r| r[0]).collect();
        let last: Vec<DVec3> = points.iter().map(|r| r[r.len() - 1]).collect();
        let closed_v = v.count() > 2 && same(&first, &last);
        Some(Surface {
            u,
            v,
            points: rows,
            closed: [closed_u, closed_v],
        })
    }

    /// The same surface, also closed on itself along u and/or v where the file says so.
    pub fn closed(mut self, u: bool, v: bool) -> Surface {
        self.closed[0] |= u;
        self.closed[1] |= v;
        self
    }

    /// The periods of u and v: the domain's length along a direction in which the surface
    /// closes on itself, else `None`.
    pub fn periods(&self) -> [Option<f64>; 2] {
        let length = |b: &Basis| {
            let (lo, hi) = b.domain();
            hi - lo
        };
        [
            self.closed[0].then(|| length(&self.u)),
            self.closed[1].then(|| length(&self.v)),
        ]
    }

    /// `(u, v)` with a parameter along a closed direction past the domain taken modulo its
    /// period (into the domain); the others as they are.
    pub fn wrap(&self, u: f64, v: f64) -> (f64, f64) {
        let wrap = |t: f64, b: &Basis, closed: bool| {
            let (lo, hi) = b.domain();
            if closed && (t < lo || t > hi) {
                lo + (t - lo).rem_euclid(hi - lo)
            } else {
                t
            }
        };
        (
            wrap(u, &self.u, self.closed[0]),
            wrap(v, &self.v, self.closed[1]),
        )
    }

    /// The point at `(u, v)`; a parameter along a closed direction is taken modulo its
    /// period ([`Surface::wrap`]).
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let (u, v) = self.wrap(u, v);
        let (su, sv) = (self.u.span(u), self.v.span(v));
        let (nu, nv) = (self.u.functions(su, u), self.v.functions(sv, v));
        let (p, q) = (self.u.degree, self.v.degree);
        let mut h = DVec4::ZERO;
        for (i, bu) in nu.iter().enumerate() {
            let row = &self.points[su - p + i];
            for (j, bv) in nv.iter().enumerate() {
                h += row[sv - q + j] * (bu * bv);
            }
        }
        h.truncate() / h.w
    }
}

/// The numbers of a list value.
fn numbers(v: &Value<'_>) -> Option<Vec<f64>> {
    v.as_list()?.iter().map(Value::as_f64).collect()
}

fn integers(v: &Value<'_>) -> Option<Vec<i64>> {
    v.as_list()?.iter().map(Value::as_i64).collect()
}

fn degree(e: &Entity<'_>, name: &'static str) -> Result<usize, GeomError> {
    e.get(name)
        .and_then(|v| v.as_i64())
        .and_then(|d| usize::try_from(d).ok())
        .ok_or_else(|| missing(e, name))
}

fn knots(
    e: &Entity<'_>,
    knots: &'static str,
    multiplicities: &'static str,
) -> Result<Vec<f64>, GeomError> {
    let k = e
        .get(knots)
        .as_ref()
        .and_then(numbers)
        .ok_or_else(|| missing(e, knots))?;
    let m = e
        .get(multiplicities)
        .as_ref()
        .and_then(integers)
        .ok_or_else(|| missing(e, multiplicities))?;
    knot_vector(&k, &m).ok_or_else(|| degenerate(e, "knots and multiplicities do not fit"))
}

/// The control points of a list of `IfcCartesianPoint`s, times `s`.
fn points(e: &Entity<'_>, list: &Value<'_>, s: f64) -> Result<Vec<DVec3>, GeomError> {
    let ids = list
        .as_list()
        .ok_or_else(|| missing(e, "ControlPointsList"))?;
    if ids.len() > MAX_CONTROL_POINTS {
        return Err(degenerate(e, "too many control points"));
    }
    ids.iter()
        .map(|v| {
            let p = v
                .as_ref_id()
                .and_then(|id| e.model().entity(id))
                .ok_or_else(|| missing(e, "ControlPointsList"))?;
            Ok(point3(p)? * s)
        })
        .collect()
}

/// True for the B-spline curves [`curve`] reads: with knots, or Bezier (rational or not).
pub fn is_curve(e: &Entity<'_>) -> bool {
    e.is_a("IfcBSplineCurveWithKnots") || e.is_a("IfcBezierCurve")
}

/// An `IfcBSplineCurveWithKnots` or (IFC2X3) `IfcBezierCurve`, rational or not, in metres
/// (`s` metres per file unit). A Bezier curve of degree p with k p + 1 control points is k
/// Bezier pieces end to end: knots 0 to k, the ends p + 1 times, the others p times (one
/// piece: what IfcOpenShell's Bezier mapping uses).
pub fn curve(e: Entity<'_>, s: f64) -> Result<Curve, GeomError> {
    let bezier = e.is_a("IfcBezierCurve");
    if !bezier && !e.is_a("IfcBSplineCurveWithKnots") {
        return Err(crate::error::unsupported(
            &e,
            "B-spline curve without knots",
        ));
    }
    let p = degree(&e, "Degree")?;
    let list = e
        .get("ControlPointsList")
        .ok_or_else(|| missing(&e, "ControlPointsList"))?;
    let pts = points(&e, &list, s)?;
    if bezier && (p == 0 || pts.len() < p + 1 || (pts.len() - 1) % p != 0) {
        return Err(degenerate(
            &e,
            "Bezier control points do not make whole pieces",
        ));
    }
    let weights = if e.is_a("IfcRationalBezierCurve") || e.is_a("IfcRationalBSplineCurveWithKnots")
    {
        Some(
            e.get("WeightsData")
                .as_ref()
                .and_then(numbers)
                .ok_or_else(|| missing(&e, "WeightsData"))?,
        )
    } else {
        None
    };
    if bezier {
        let pieces = (pts.len() - 1) / p;
        let knots: Vec<f64> = (0..=pieces).map(|k| k as f64).collect();
        let mult: Vec<i64> = (0..=pieces)
            .map(|k| {
                if k == 0 || k == pieces {
                    p as i64 + 1
                } else {
                    p as i64
                }
            })
            .collect();
        let k = knot_vector(&knots, &mult)
            .ok_or_else(|| degenerate(&e, "degree too high for a Bezier curve"))?;
        return Curve::new(p, k, &pts, weights.as_deref())
            .ok_or_else(|| degenerate(&e, "degree, control points or weights do not fit"));
    }
    let k = knots(&e, "Knots", "KnotMultiplicities")?;
    Curve::new(p, k, &pts, weights.as_deref())
        .ok_or_else(|| degenerate(&e, "degree, knots, control points or weights do not fit"))
}

/// An `IfcBSplineSurfaceWithKnots` (rational or not) in metres.
pub fn surface(e: Entity<'_>, s: f64) -> Result<Surface, GeomError> {
    if !e.is_a("IfcBSplineSurfaceWithKnots") {
        return Err(crate::error::unsupported(
            &e,
            "B-spline surface without knots",
        ));
    }
    let (p, q) = (degree(&e, "UDegree")?, degree(&e, "VDegree")?);
    let list = e
        .get("ControlPointsList")
        .ok_or_else(|| missing(&e, "ControlPointsList"))?;
    let rows = list
        .as_list()
        .ok_or_else(|| missing(&e, "ControlPointsList"))?;
    let pts: Vec<Vec<DVec3>> = rows
        .iter()
        .map(|r| points(&e, r, s))
        .collect::<Result<_, _>>()?;
    if pts.iter().map(Vec::len).sum::<usize>() > MAX_CONTROL_POINTS {
        return Err(degenerate(&e, "too many control points"));
    }
    let weights = if e.is_a("IfcRationalBSplineSurfaceWithKnots") {
        let w = e
            .get("WeightsData")
            .ok_or_else(|| missing(&e, "WeightsData"))?;
        Some(
            w.as_list()
                .and_then(|rows| rows.iter().map(numbers).collect::<Option<Vec<_>>>())
                .ok_or_else(|| missing(&e, "WeightsData"))?,
        )
    } else {
        None
    };
    let nu = pts.len();
    let nv = pts.first().map_or(0, Vec::len);
    let u = Basis::new(p, knots(&e, "UKnots", "UMultiplicities")?, nu);
    let v = Basis::new(q, knots(&e, "VKnots", "VMultiplicities")?, nv);
    let bad = || degenerate(&e, "degrees, knots, control points or weights do not fit");
    let closed = |name| e.get(name).and_then(|v| v.as_enum()) == Some("T");
    Surface::new(
        u.ok_or_else(bad)?,
        v.ok_or_else(bad)?,
        &pts,
        weights.as_deref(),
    )
    .map(|b| b.closed(closed("UClosed"), closed("VClosed")))
    .ok_or_else(bad)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_functions_sum_to_one_and_vanish_outside() {
        let knots = knot_vector(&[0.0, 1.0, 2.5, 3.0, 4.0], &[4, 1, 2, 1, 4]).unwrap();
        let b = Basis::new(3, knots, 8).unwrap();
        assert_eq!(b.domain(), (0.0, 4.0));
        assert_eq!(b.breaks(), vec![0.0, 1.0, 2.5, 3.0, 4.0]);
        for k in 0..=400 {
            let t = 4.0 * k as f64 / 400.0;
            let span = b.span(t);
            assert!(
                b.knots[span] <= t && (t < b.knots[span + 1] || t == 4.0),
                "{t} {span}"
            );
            let n = b.functions(span, t);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{t}: {n:?}");
            assert!(n.iter().all(|&x| x >= -1e-15));
        }
        assert!(knot_vector(&[0.0, 1.0], &[2]).is_none());
        assert!(knot_vector(&[1.0, 0.0], &[2, 2]).is_none());
        assert!(Basis::new(3, vec![0.0; 7], 3).is_none());
    }

    proptest::proptest! {
        /// Any knot vector the constructor takes evaluates without panicking, anywhere
        /// (outside the domain and NaN too), and its basis sums to one inside the domain.
        #[test]
        fn any_accepted_basis_evaluates(
            degree in 1usize..5,
            gaps in proptest::collection::vec(0.0f64..2.0, 2..16),
            count in 2usize..12,
            t in -1.0f64..40.0,
        ) {
            let mut knots = vec![0.0];
            for g in &gaps {
                knots.push(knots.last().unwrap() + g);
            }
            knots.truncate(count + degree + 1);
            if let Some(b) = Basis::new(degree, knots, count) {
                for x in [t, f64::NAN, f64::INFINITY, -f64::INFINITY] {
                    let n = b.functions(b.span(x), x);
                    let (lo, hi) = b.domain();
                    if (lo..=hi).contains(&x) {
                        proptest::prop_assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-9);
                    }
                }
                let pts: Vec<DVec3> = (0..count).map(|i| DVec3::splat(i as f64)).collect();
                let c = Curve::new(degree, b.knots.clone(), &pts, None).unwrap();
                let _ = c.point(t);
                proptest::prop_assert!(c.sample().len() >= 2);
            }
        }
    }

    #[test]
    fn rational_quarter_circle_lies_on_the_circle() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let c = Curve::new(
            2,
            knot_vector(&[0.0, 1.0], &[3, 3]).unwrap(),
            &[DVec3::X * 2.0, DVec3::new(2.0, 2.0, 0.0), DVec3::Y * 2.0],
            Some(&[1.0, h, 1.0]),
        )
        .unwrap();
        for k in 0..=100 {
            let p = c.point(k as f64 / 100.0);
            assert!((p.length() - 2.0).abs() < 1e-9, "{p}");
        }
        let pts = c.sample();
        assert!(pts.iter().all(|p| (p.length() - 2.0).abs() < 1e-9));
        assert_eq!(pts[0], DVec3::X * 2.0);
        assert!((pts.last().unwrap() - DVec3::Y * 2.0).length() < 1e-12);
        // Chords no longer than the arc rule's (5 degrees at radius 2: 0.1745 m).
        assert!(
            pts.windows(2).all(|w| w[0].distance(w[1]) <= 0.175),
            "{}",
            pts.len()
        );
        let t = c.parameter_of(DVec3::new(h, h, 0.0) * 2.0);
        assert!((c.point(t) - DVec3::new(h, h, 0.0) * 2.0).length() < 1e-9);
        // Without weights the middle bulges inwards.
        let plain = Curve::new(
            2,
            knot_vector(&[0.0, 1.0], &[3, 3]).unwrap(),
            &[DVec3::X * 2.0, DVec3::new(2.0, 2.0, 0.0), DVec3::Y * 2.0],
            None,
        )
        .unwrap();
        assert!((plain.point(0.5) - DVec3::new(1.5, 1.5, 0.0)).length() < 1e-12);
    }

    #[test]
    fn bilinear_surface_is_exact() {
        let b = || Basis::new(1, vec![0.0, 0.0, 1.0, 1.0], 2).unwrap();
        let s = Surface::new(
            b(),
            b(),
            &[
                vec![DVec3::ZERO, DVec3::new(0.0, 2.0, 0.0)],
                vec![DVec3::new(3.0, 0.0, 0.0), DVec3::new(3.0, 2.0, 1.0)],
            ],
            None,
        )
        .unwrap();
        assert!((s.point(0.5, 0.5) - DVec3::new(1.5, 1.0, 0.25)).length() < 1e-12);
        assert!((s.point(1.0, 1.0) - DVec3::new(3.0, 2.0, 1.0)).length() < 1e-12);
    }
}

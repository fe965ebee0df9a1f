//! The basis curves of linear referencing, evaluated by distance along: `IfcCompositeCurve` of
//! `IfcCurveSegment`s (an alignment in plan), `IfcGradientCurve` (that plan curve with its
//! vertical segments: constant gradient, parabolic and circular arcs, as distance along against
//! height), `IfcSegmentedReferenceCurve` (cant is not applied: its base curve stands for it)
//! and `IfcOffsetCurveByDistances` (its basis curve with the lateral and vertical offsets of
//! its `OffsetValues`, interpolated linearly by distance along, constant past either end).
//! Any other `IfcCurve` [`crate::curve`] reads is taken as a polyline in plan, with the heights
//! of its points when it is drawn in 3D (linear between them; distance along it is measured in
//! space, as IfcOpenShell does).
//!
//! Distance along a gradient curve is measured in plan, as IfcOpenShell does; past either end a
//! curve continues straight along its end tangent.

use glam::{DVec2, DVec3};
use poinav_ifc::Entity;

use crate::alignment_curve::{CurveSegment, Frame2};
use crate::curve::polyline;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::unit_assignment::Units;

/// The frame of a basis curve at one distance along it, in metres: `tangent` is the direction
/// of travel (climbing with the gradient), `left` is horizontal and square to it, `normal`
/// completes the right-handed frame (up, tilted back by the gradient).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame3 {
    /// The point on the curve.
    pub origin: DVec3,
    /// Unit direction of travel.
    pub tangent: DVec3,
    /// Unit horizontal direction to the left of travel.
    pub left: DVec3,
    /// Unit normal, `tangent × left`.
    pub normal: DVec3,
}

/// Segments laid end to end, each starting at the distance the previous ones add up to.
#[derive(Debug, Clone, PartialEq)]
struct Chain {
    segments: Vec<CurveSegment>,
    starts: Vec<f64>,
}

impl Chain {
    fn read(composite: Entity<'_>) -> Result<Chain, GeomError> {
        let mut segments = Vec::new();
        for s in composite.get_refs("Segments") {
            segments.push(CurveSegment::read(s)?);
        }
        if segments.is_empty() {
            return Err(missing(&composite, "Segments"));
        }
        let mut starts = Vec::with_capacity(segments.len());
        let mut d = 0.0;
        for s in &segments {
            starts.push(d);
            d += s.length();
        }
        Ok(Chain { segments, starts })
    }

    /// The segment holding distance `d` (the first or last one beyond the ends) and the
    /// distance into it.
    fn locate(&self, d: f64) -> (&CurveSegment, f64) {
        let i = self.starts.partition_point(|&s| s <= d).saturating_sub(1);
        // Zero-length segments at the end (IFC's closing segment) hold no distance.
        let mut i = i;
        while i > 0 && self.segments[i].length() == 0.0 {
            i -= 1;
        }
        (&self.segments[i], d - self.starts[i])
    }

    fn eval(&self, d: f64) -> Frame2 {
        let (seg, u) = self.locate(d);
        along(seg, u)
    }
}

/// A segment at `u`, continued straight along its end tangents outside `0..=length`.
fn along(seg: &CurveSegment, u: f64) -> Frame2 {
    let clamped = u.clamp(0.0, seg.length());
    let f = seg.eval(clamped);
    Frame2 {
        point: f.point + f.tangent * (u - clamped),
        tangent: f.tangent,
    }
}

/// The plan curve of a basis curve.
#[derive(Debug, Clone, PartialEq)]
enum Plan {
    Segments(Chain),
    /// A polyline in plan with the height of each point (file units; zero for a 2D curve).
    Polyline {
        points: Vec<DVec2>,
        along: Vec<f64>,
        heights: Vec<f64>,
    },
}

/// How far `d` lies from `along[i - 1]` towards `along[i]`, as a fraction (beyond 0..1 past
/// the polyline's ends).
fn fraction(along: &[f64], i: usize, d: f64) -> f64 {
    let span = along[i] - along[i - 1];
    if span > 0.0 {
        (d - along[i - 1]) / span
    } else {
        0.0
    }
}

impl Plan {
    /// The height and slope (rise over plan distance) of a polyline at `d` (distance along its
    /// points in space), linear between its points and constant past its ends; `None` for a
    /// chain of segments.
    fn height(&self, d: f64) -> Option<(f64, f64)> {
        let Plan::Polyline {
            points,
            along,
            heights,
        } = self
        else {
            return None;
        };
        let n = along.len();
        if d <= along[0] {
            return Some((heights[0], 0.0));
        }
        if d >= along[n - 1] {
            return Some((heights[n - 1], 0.0));
        }
        let i = along.partition_point(|&a| a <= d).clamp(1, n - 1);
        let (run, rise) = (
            points[i].distance(points[i - 1]),
            heights[i] - heights[i - 1],
        );
        let slope = if run > 0.0 { rise / run } else { 0.0 };
        Some((heights[i - 1] + rise * fraction(along, i, d), slope))
    }

    fn eval(&self, d: f64) -> Frame2 {
        match self {
            Plan::Segments(c) => c.eval(d),
            Plan::Polyline { points, along, .. } => {
                let i = along
                    .partition_point(|&a| a <= d)
                    .clamp(1, points.len() - 1);
                let (p, q) = (points[i - 1], points[i]);
                let t = (q - p).normalize_or(DVec2::X);
                Frame2 {
                    point: p + (q - p) * fraction(along, i, d),
                    tangent: t,
                }
            }
        }
    }
}

/// The vertical segments of a gradient curve, sorted by the distance along where they start.
#[derive(Debug, Clone, PartialEq)]
struct Vertical {
    segments: Vec<CurveSegment>,
}

impl Vertical {
    /// Height and gradient at distance `d` along the plan curve.
    fn at(&self, d: f64) -> (f64, f64) {
        let i = self
            .segments
            .partition_point(|s| s.start_point().x <= d)
            .saturating_sub(1);
        let seg = &self.segments[i];
        // Solve x(u) = d for the distance u along the segment (x grows with u).
        let f0 = seg.eval(0.0);
        let mut u = (d - f0.point.x) / f0.tangent.x.max(1e-9);
        for _ in 0..30 {
            let f = along(seg, u);
            let step = (f.point.x - d) / f.tangent.x.max(1e-9);
            u -= step;
            if step.abs() < 1e-10 {
                break;
            }
        }
        let f = along(seg, u);
        let slope = f.tangent.y / f.tangent.x.max(1e-9);
        (f.point.y + slope * (d - f.point.x), slope)
    }
}

/// A curve linear placements and sectioned solids are measured along.
#[derive(Debug, Clone, PartialEq)]
pub struct BasisCurve {
    plan: Plan,
    vertical: Option<Vertical>,
    metres_per_unit: f64,
    /// Offset curves' offsets, innermost first: (distance along in file units, lateral and
    /// vertical offsets in metres), by distance.
    offsets: Vec<Vec<(f64, f64, f64)>>,
}

/// A number of an `IfcPointByDistanceExpression` (`$` is zero unless `required`).
fn expression_number(e: &Entity<'_>, name: &'static str, required: bool) -> Result<f64, GeomError> {
    match e.get(name) {
        None if !required => Ok(0.0),
        v => v
            .and_then(|v| v.as_f64())
            .filter(|x| x.is_finite())
            .ok_or_else(|| missing(e, name)),
    }
}

/// The lateral and vertical offsets at distance `d` of one offset curve's `offsets`.
fn offset_at(offsets: &[(f64, f64, f64)], d: f64) -> (f64, f64) {
    let i = offsets.partition_point(|o| o.0 <= d);
    if i == 0 {
        return (offsets[0].1, offsets[0].2);
    }
    if i == offsets.len() {
        let o = offsets[i - 1];
        return (o.1, o.2);
    }
    let (a, b) = (offsets[i - 1], offsets[i]);
    let t = if b.0 > a.0 {
        (d - a.0) / (b.0 - a.0)
    } else {
        0.0
    };
    (a.1 + (b.1 - a.1) * t, a.2 + (b.2 - a.2) * t)
}

impl BasisCurve {
    /// Reads `curve` (see the module documentation for the kinds).
    pub fn read(curve: Entity<'_>, units: &Units) -> Result<BasisCurve, GeomError> {
        let metres_per_unit = units.metres_per_unit;
        if curve.is_a("IfcOffsetCurveByDistances") {
            let mut basis =
                BasisCurve::read(required_ref(&curve, "BasisCurve", "IfcCurve")?, units)?;
            let mut offsets = Vec::new();
            for v in curve.get_refs("OffsetValues") {
                if !v.is_a("IfcPointByDistanceExpression") {
                    return Err(unsupported(&v, "expected an IfcPointByDistanceExpression"));
                }
                offsets.push((
                    expression_number(&v, "DistanceAlong", true)?,
                    expression_number(&v, "OffsetLateral", false)? * metres_per_unit,
                    expression_number(&v, "OffsetVertical", false)? * metres_per_unit,
                ));
            }
            if offsets.is_empty() {
                return Err(missing(&curve, "OffsetValues"));
            }
            offsets.sort_by(|a, b| a.0.total_cmp(&b.0));
            basis.offsets.push(offsets);
            return Ok(basis);
        }
        if curve.is_a("IfcSegmentedReferenceCurve") {
            return BasisCurve::read(required_ref(&curve, "BaseCurve", "IfcCurve")?, units);
        }
        if curve.is_a("IfcGradientCurve") {
            let base = required_ref(&curve, "BaseCurve", "IfcBoundedCurve")?;
            let plan = BasisCurve::read(base, units)?.plan;
            let mut segments = Vec::new();
            for s in curve.get_refs("Segments") {
                segments.push(CurveSegment::read(s)?);
            }
            if segments.is_empty() {
                return Err(missing(&curve, "Segments"));
            }
            segments.sort_by(|a, b| a.start_point().x.total_cmp(&b.start_point().x));
            return Ok(BasisCurve {
                plan,
                vertical: Some(Vertical { segments }),
                metres_per_unit,
                offsets: Vec::new(),
            });
        }
        if curve.is_a("IfcCompositeCurve")
            && curve
                .get_refs("Segments")
                .first()
                .is_some_and(|s| s.is_a("IfcCurveSegment"))
        {
            return Ok(BasisCurve {
                plan: Plan::Segments(Chain::read(curve)?),
                vertical: None,
                metres_per_unit,
                offsets: Vec::new(),
            });
        }
        if !curve.is_a("IfcCurve") {
            return Err(unsupported(&curve, "expected a basis curve"));
        }
        let file_units = Units {
            metres_per_unit: 1.0,
            ..*units
        };
        let points = polyline(curve, &file_units)?;
        if points.len() < 2 {
            return Err(degenerate(&curve, "basis curve has fewer than two points"));
        }
        // The heights of a curve drawn in 3D, where its 3D path has the same points in plan
        // (IfcOpenShell keeps them: a directrix at z = -0.2 puts the solid 0.2 lower).
        let heights = crate::curve3d::path(curve, &file_units)
            .ok()
            .filter(|p| {
                p.points.len() == points.len()
                    && p.points
                        .iter()
                        .zip(&points)
                        .all(|(a, b)| a.truncate().distance(*b) <= 1e-9 * b.length().max(1.0))
            })
            .map_or_else(
                || vec![0.0; points.len()],
                |p| p.points.iter().map(|q| q.z).collect(),
            );
        // Distance along is measured in space (as IfcOpenShell does for a plain curve).
        let mut along = vec![0.0];
        for k in 1..points.len() {
            let step = points[k].extend(heights[k]) - points[k - 1].extend(heights[k - 1]);
            along.push(along[k - 1] + step.length());
        }
        Ok(BasisCurve {
            plan: Plan::Polyline {
                points,
                along,
                heights,
            },
            vertical: None,
            metres_per_unit,
            offsets: Vec::new(),
        })
    }

    /// The frame at `distance` along the curve, given in file units; the result in metres.
    pub fn frame(&self, distance: f64) -> Frame3 {
        let f = self.plan.eval(distance);
        let (z, slope) = match &self.vertical {
            Some(v) => v.at(distance),
            None => self.plan.height(distance).unwrap_or((0.0, 0.0)),
        };
        let tangent = DVec3::new(f.tangent.x, f.tangent.y, slope).normalize();
        let left = DVec3::new(-f.tangent.y, f.tangent.x, 0.0);
        let normal = tangent.cross(left);
        let mut origin = f.point.extend(z) * self.metres_per_unit;
        for o in &self.offsets {
            let (lateral, vertical) = offset_at(o, distance);
            origin += left * lateral + normal * vertical;
        }
        Frame3 {
            origin,
            tangent,
            left,
            normal,
        }
    }

    /// The plan curve's length, or `None` for a polyline; for segment chains the sum of the
    /// segments' lengths (file units).
    pub fn length(&self) -> f64 {
        match &self.plan {
            Plan::Segments(c) => {
                c.starts.last().copied().unwrap_or(0.0)
                    + c.segments.last().map_or(0.0, CurveSegment::length)
            }
            Plan::Polyline { along, .. } => along.last().copied().unwrap_or(0.0),
        }
    }
}

//! `IfcCurveSegment`: one segment of an IFC4X3 alignment curve, evaluated by distance along
//! it in its composite curve's 2D coordinates (file units). Parent curves: `IfcLine`,
//! `IfcCircle`, `IfcClothoid`, `IfcCosineSpiral`, `IfcSineSpiral`, the second-, third- and
//! seventh-order polynomial spirals, `IfcPolynomialCurve` and `IfcPolyline`.
//!
//! The segment is the parent curve from `SegmentStart` for `|SegmentLength|` (a negative length
//! runs the parent backwards), moved so that its start lies at `Placement`'s location with its
//! direction of travel along `Placement`'s x axis (IFC 4.3 8.9.3.28, the same mapping as
//! IfcOpenShell). Spirals have no closed form: their points are the integrals of the cosine and
//! sine of the heading angle, by adaptive Gauss-Legendre quadrature to [`INTEGRATION_TOLERANCE`].

use glam::{DAffine2, DMat2, DVec2};
use poinav_ifc::Entity;

use crate::axis2_placement::axis2placement_2d;
use crate::cartesian_point::point2;
use crate::direction::direction;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};

/// Absolute tolerance of the quadrature of spiral points, in file length units per unit of
/// length integrated (1e-10: far below a millimetre over the longest alignment).
pub const INTEGRATION_TOLERANCE: f64 = 1e-10;

/// A point of a planar curve and the unit tangent in its direction of travel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame2 {
    /// The point.
    pub point: DVec2,
    /// The unit tangent.
    pub tangent: DVec2,
}

/// The heading angle of a spiral as a function of the arc length `s` from its origin
/// (IFC 4.3 8.9.3.75 ff.; terms as IfcOpenShell evaluates them).
#[derive(Debug, Clone, PartialEq)]
enum Heading {
    /// `IfcClothoid`: θ = sign(A)·s²/(2A²).
    Clothoid(f64),
    /// Polynomial spirals: Σ sign(Aᵢ)·s^(i+1)/((i+1)·|Aᵢ|^(i+1)), terms `(i, Aᵢ)`.
    Polynomial(Vec<(i32, f64)>),
    /// `IfcCosineSpiral`: θ = s/A₀ + (L/π)/A₁·sin(πs/L).
    Cosine {
        constant: Option<f64>,
        cosine: f64,
        length: f64,
    },
    /// `IfcSineSpiral`: θ = s/A₀ + sign(A₁)(s/A₁)²/2 − L/(2πA₂)·(cos(2πs/L) − 1).
    Sine {
        constant: Option<f64>,
        linear: Option<f64>,
        sine: f64,
        length: f64,
    },
}

impl Heading {
    fn angle(&self, s: f64) -> f64 {
        use std::f64::consts::PI;
        match self {
            Heading::Clothoid(a) => a.signum() * s * s / (2.0 * a * a),
            Heading::Polynomial(terms) => terms
                .iter()
                .map(|&(i, a)| {
                    let n = f64::from(i + 1);
                    a.signum() * s.powi(i + 1) / (n * a.abs().powi(i + 1))
                })
                .sum(),
            Heading::Cosine {
                constant,
                cosine,
                length,
            } => constant.map_or(0.0, |a| s / a) + length / PI / cosine * (PI * s / length).sin(),
            Heading::Sine {
                constant,
                linear,
                sine,
                length,
            } => {
                constant.map_or(0.0, |a| s / a)
                    + linear.map_or(0.0, |a| a.signum() * (s / a).powi(2) / 2.0)
                    - length / (2.0 * PI * sine) * ((2.0 * PI * s / length).cos() - 1.0)
            }
        }
    }

    /// The point at arc length `s` from the spiral's origin, in its own coordinates.
    fn point(&self, s: f64) -> DVec2 {
        let f = |t: f64| {
            let a = self.angle(t);
            DVec2::new(a.cos(), a.sin())
        };
        integrate(&f, 0.0, s)
    }
}

/// Nodes and weights of 5-point Gauss-Legendre quadrature on [-1, 1].
const GAUSS: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

fn gauss(f: &dyn Fn(f64) -> DVec2, a: f64, b: f64) -> DVec2 {
    let (m, h) = ((a + b) / 2.0, (b - a) / 2.0);
    GAUSS.iter().map(|&(x, w)| f(m + h * x) * w).sum::<DVec2>() * h
}

/// ∫ₐᵇ f by adaptive Gauss-Legendre quadrature: panels of at most 10 units, halved until the
/// halves agree with the whole to [`INTEGRATION_TOLERANCE`] per unit length (depth at most 24).
pub fn integrate(f: &dyn Fn(f64) -> DVec2, a: f64, b: f64) -> DVec2 {
    fn adapt(f: &dyn Fn(f64) -> DVec2, a: f64, b: f64, whole: DVec2, depth: u32) -> DVec2 {
        let m = (a + b) / 2.0;
        let (l, r) = (gauss(f, a, m), gauss(f, m, b));
        if depth >= 24
            || (l + r - whole).length() <= INTEGRATION_TOLERANCE * (b - a).abs().max(1e-3)
        {
            return l + r;
        }
        adapt(f, a, m, l, depth + 1) + adapt(f, m, b, r, depth + 1)
    }
    let panels = ((b - a).abs() / 10.0).ceil().clamp(1.0, 1e6) as usize;
    let h = (b - a) / panels as f64;
    (0..panels)
        .map(|i| {
            let (x0, x1) = (a + h * i as f64, a + h * (i + 1) as f64);
            adapt(f, x0, x1, gauss(f, x0, x1), 0)
        })
        .sum()
}

/// A parent curve, evaluated by arc length from its own origin, in its own coordinates.
#[derive(Debug, Clone, PartialEq)]
enum Parent {
    Line {
        origin: DVec2,
        direction: DVec2,
    },
    Circle {
        position: DAffine2,
        radius: f64,
    },
    Spiral {
        position: DAffine2,
        heading: Heading,
    },
    Polynomial {
        position: DAffine2,
        x: Vec<f64>,
        y: Vec<f64>,
    },
    Polyline {
        points: Vec<DVec2>,
        along: Vec<f64>,
    },
}

fn poly(c: &[f64], t: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &k| acc * t + k)
}

fn poly_derivative(c: &[f64], t: f64) -> f64 {
    c.iter()
        .enumerate()
        .skip(1)
        .rev()
        .fold(0.0, |acc, (i, &k)| acc * t + k * i as f64)
}

impl Parent {
    fn eval(&self, s: f64) -> Frame2 {
        match self {
            Parent::Line { origin, direction } => Frame2 {
                point: *origin + *direction * s,
                tangent: *direction,
            },
            Parent::Circle { position, radius } => {
                let a = s / radius;
                let (sin, cos) = a.sin_cos();
                Frame2 {
                    point: position.transform_point2(DVec2::new(cos, sin) * *radius),
                    tangent: position.transform_vector2(DVec2::new(-sin, cos)),
                }
            }
            Parent::Spiral { position, heading } => {
                let a = heading.angle(s);
                Frame2 {
                    point: position.transform_point2(heading.point(s)),
                    tangent: position.transform_vector2(DVec2::new(a.cos(), a.sin())),
                }
            }
            Parent::Polynomial { position, x, y } => {
                let t = self.polynomial_parameter(s, x, y);
                let d = DVec2::new(poly_derivative(x, t), poly_derivative(y, t));
                Frame2 {
                    point: position.transform_point2(DVec2::new(poly(x, t), poly(y, t))),
                    tangent: position.transform_vector2(d.try_normalize().unwrap_or(DVec2::X)),
                }
            }
            Parent::Polyline { points, along } => {
                let i = along
                    .partition_point(|&a| a <= s)
                    .clamp(1, points.len() - 1);
                let (p, q) = (points[i - 1], points[i]);
                let d = (q - p).normalize_or(DVec2::X);
                Frame2 {
                    point: p + d * (s - along[i - 1]),
                    tangent: d,
                }
            }
        }
    }

    /// The parameter t of a polynomial curve at arc length `s` from t = 0 (Newton's method on
    /// the arc length integral).
    fn polynomial_parameter(&self, s: f64, x: &[f64], y: &[f64]) -> f64 {
        let speed = |t: f64| DVec2::new(poly_derivative(x, t), poly_derivative(y, t)).length();
        let arc = |t: f64| integrate(&|u| DVec2::new(speed(u), 0.0), 0.0, t).x;
        let mut t = s / speed(0.0).max(1e-12);
        for _ in 0..50 {
            let v = speed(t).max(1e-12);
            let step = (arc(t) - s) / v;
            t -= step;
            if step.abs() < 1e-12 * s.abs().max(1.0) {
                break;
            }
        }
        t
    }

    fn read(curve: Entity<'_>, segment_length: f64) -> Result<Parent, GeomError> {
        let position = |c: &Entity<'_>| -> Result<DAffine2, GeomError> {
            match c.get("Position") {
                None => Ok(DAffine2::IDENTITY),
                Some(_) => {
                    axis2placement_2d(required_ref(c, "Position", "IfcAxis2Placement2D")?, 1.0)
                }
            }
        };
        let number = |c: &Entity<'_>, name: &'static str| -> Result<f64, GeomError> {
            let v = c.get_f64(name).ok_or_else(|| missing(c, name))?;
            if v.is_finite() && v != 0.0 {
                Ok(v)
            } else {
                Err(degenerate(c, "spiral term is zero or not a number"))
            }
        };
        let optional = |c: &Entity<'_>, name: &'static str| -> Result<Option<f64>, GeomError> {
            match c.get(name) {
                None => Ok(None),
                Some(_) => number(c, name).map(Some),
            }
        };
        if curve.is_a("IfcLine") {
            let origin = point2(required_ref(&curve, "Pnt", "IfcCartesianPoint")?)?;
            let v = required_ref(&curve, "Dir", "IfcVector")?;
            let d = direction(required_ref(&v, "Orientation", "IfcDirection")?)?.truncate();
            let direction = d
                .try_normalize()
                .ok_or_else(|| degenerate(&v, "line direction has no x or y component"))?;
            Ok(Parent::Line { origin, direction })
        } else if curve.is_a("IfcCircle") {
            let radius = number(&curve, "Radius")?.abs();
            Ok(Parent::Circle {
                position: position(&curve)?,
                radius,
            })
        } else if curve.is_a("IfcClothoid") {
            Ok(Parent::Spiral {
                position: position(&curve)?,
                heading: Heading::Clothoid(number(&curve, "ClothoidConstant")?),
            })
        } else if curve.is_a("IfcCosineSpiral") {
            Ok(Parent::Spiral {
                position: position(&curve)?,
                heading: Heading::Cosine {
                    constant: optional(&curve, "ConstantTerm")?,
                    cosine: number(&curve, "CosineTerm")?,
                    length: segment_length.abs().max(1e-12),
                },
            })
        } else if curve.is_a("IfcSineSpiral") {
            Ok(Parent::Spiral {
                position: position(&curve)?,
                heading: Heading::Sine {
                    constant: optional(&curve, "ConstantTerm")?,
                    linear: optional(&curve, "LinearTerm")?,
                    sine: number(&curve, "SineTerm")?,
                    length: segment_length.abs().max(1e-12),
                },
            })
        } else if curve.is_a("IfcSecondOrderPolynomialSpiral")
            || curve.is_a("IfcThirdOrderPolynomialSpiral")
            || curve.is_a("IfcSeventhOrderPolynomialSpiral")
        {
            const NAMES: [&str; 8] = [
                "ConstantTerm",
                "LinearTerm",
                "QuadraticTerm",
                "CubicTerm",
                "QuarticTerm",
                "QuinticTerm",
                "SexticTerm",
                "SepticTerm",
            ];
            let mut terms = Vec::new();
            for (i, name) in (0i32..).zip(NAMES) {
                if curve.attr_index(name).is_ok() {
                    if let Some(a) = optional(&curve, name)? {
                        terms.push((i, a));
                    }
                }
            }
            Ok(Parent::Spiral {
                position: position(&curve)?,
                heading: Heading::Polynomial(terms),
            })
        } else if curve.is_a("IfcPolynomialCurve") {
            let coefficients = |name| -> Vec<f64> {
                curve
                    .get(name)
                    .and_then(|v| {
                        v.as_list()
                            .map(|l| l.iter().filter_map(|x| x.as_f64()).collect())
                    })
                    .unwrap_or_default()
            };
            Ok(Parent::Polynomial {
                position: position(&curve)?,
                x: coefficients("CoefficientsX"),
                y: coefficients("CoefficientsY"),
            })
        } else if curve.is_a("IfcPolyline") {
            let points: Vec<DVec2> = curve
                .get_refs("Points")
                .into_iter()
                .map(point2)
                .collect::<Result<_, _>>()?;
            if points.len() < 2 {
                return Err(missing(&curve, "Points"));
            }
            let mut along = vec![0.0];
            for w in points.windows(2) {
                along.push(along.last().copied().unwrap_or(0.0) + w[0].distance(w[1]));
            }
            Ok(Parent::Polyline { points, along })
        } else {
            Err(unsupported(&curve, "parent curve of a curve segment"))
        }
    }
}

/// One `IfcCurveSegment`, ready to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveSegment {
    /// Maps the parent curve's coordinates to the composite curve's: `Placement` after moving
    /// the trimmed start to the origin with its direction of travel along +x.
    to_curve: DAffine2,
    parent: Parent,
    start: f64,
    length: f64,
}

impl CurveSegment {
    /// Reads an `IfcCurveSegment` (lengths stay in file units).
    pub fn read(segment: Entity<'_>) -> Result<CurveSegment, GeomError> {
        if !segment.is_a("IfcCurveSegment") {
            return Err(unsupported(&segment, "expected an IfcCurveSegment"));
        }
        let measure = |name: &'static str| -> Result<f64, GeomError> {
            let v = segment.get(name).ok_or_else(|| missing(&segment, name))?;
            if let poinav_ifc::Value::Typed(kind, _) = &v {
                if kind.eq_ignore_ascii_case("IFCPARAMETERVALUE") {
                    return Err(unsupported(
                        &segment,
                        "curve segment bounds as parameter values",
                    ));
                }
            }
            v.as_f64()
                .filter(|x| x.is_finite())
                .ok_or_else(|| missing(&segment, name))
        };
        let start = measure("SegmentStart")?;
        let length = measure("SegmentLength")?;
        let placement = axis2placement_2d(
            required_ref(&segment, "Placement", "IfcAxis2Placement2D")?,
            1.0,
        )?;
        let parent = Parent::read(required_ref(&segment, "ParentCurve", "IfcCurve")?, length)?;
        let sign = if length < 0.0 { -1.0 } else { 1.0 };
        let at_start = parent.eval(start);
        let t = at_start.tangent * sign;
        // The map taking the start to the origin and the direction of travel to +x.
        let normalise = DAffine2::from_mat2(DMat2::from_cols(t, t.perp()).transpose())
            * DAffine2::from_translation(-at_start.point);
        Ok(CurveSegment {
            to_curve: placement * normalise,
            parent,
            start,
            length,
        })
    }

    /// The length of the segment along it (file units, never negative).
    pub fn length(&self) -> f64 {
        self.length.abs()
    }

    /// The point and direction of travel at distance `u` from the segment's start (file
    /// units; `u` outside `0..=length` extrapolates the parent curve).
    pub fn eval(&self, u: f64) -> Frame2 {
        let sign = if self.length < 0.0 { -1.0 } else { 1.0 };
        let f = self.parent.eval(self.start + sign * u);
        Frame2 {
            point: self.to_curve.transform_point2(f.point),
            tangent: self
                .to_curve
                .transform_vector2(f.tangent * sign)
                .normalize_or(DVec2::X),
        }
    }

    /// Where the segment starts (its `Placement` location).
    pub fn start_point(&self) -> DVec2 {
        self.to_curve.translation
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fresnel integrals by their power series (exact to 1e-15 for |x| < 3).
    fn fresnel(x: f64) -> (f64, f64) {
        let (mut c, mut s) = (0.0, 0.0);
        // Direct series: C(x) = Σ (-1)^n (π/2)^(2n) x^(4n+1) / ((2n)! (4n+1)),
        // S(x) = Σ (-1)^n (π/2)^(2n+1) x^(4n+3) / ((2n+1)! (4n+3)).
        let mut term_fact = 1.0; // k!
        for k in 0..60 {
            if k > 0 {
                term_fact *= k as f64;
            }
            let p = std::f64::consts::FRAC_PI_2.powi(k) * x.powi(2 * k + 1)
                / (term_fact * (2 * k + 1) as f64);
            match k % 4 {
                0 => c += p,
                1 => s += p,
                2 => c -= p,
                _ => s -= p,
            }
        }
        (c, s)
    }

    #[test]
    fn clothoid_end_point_matches_the_fresnel_closed_form() {
        // x(s) = A√π C(s/(A√π)), y(s) = A√π S(s/(A√π)).
        let a = 150.0;
        let heading = Heading::Clothoid(a);
        let scale = a * std::f64::consts::PI.sqrt();
        for s in [10.0, 84.185, 200.0, 300.0] {
            let (c, sn) = fresnel(s / scale);
            let p = heading.point(s);
            assert!(
                (p.x - scale * c).abs() < 1e-8,
                "{s}: {} vs {}",
                p.x,
                scale * c
            );
            assert!(
                (p.y - scale * sn).abs() < 1e-8,
                "{s}: {} vs {}",
                p.y,
                scale * sn
            );
        }
        // A negative constant turns the other way.
        let q = Heading::Clothoid(-a).point(200.0);
        let p = heading.point(200.0);
        assert!((q.x - p.x).abs() < 1e-12 && (q.y + p.y).abs() < 1e-12);
    }

    #[test]
    fn arc_segment_ends_on_its_circle_and_distance_is_arc_length() {
        let position = DAffine2::from_translation(DVec2::new(268.8, -103.3))
            * DAffine2::from_mat2(DMat2::from_angle(2.775));
        for length in [-362.6, 150.0] {
            let parent = Parent::Circle {
                position,
                radius: 288.0,
            };
            let seg = CurveSegment {
                to_curve: DAffine2::IDENTITY,
                parent: parent.clone(),
                start: 12.0,
                length,
            };
            // Build the normalisation as read() does.
            let sign = length.signum();
            let f = parent.eval(12.0);
            let t = f.tangent * sign;
            let placement = DAffine2::from_translation(DVec2::new(10.0, 20.0))
                * DAffine2::from_mat2(DMat2::from_angle(0.3));
            let seg = CurveSegment {
                to_curve: placement
                    * DAffine2::from_mat2(DMat2::from_cols(t, t.perp()).transpose())
                    * DAffine2::from_translation(-f.point),
                ..seg
            };
            let start = seg.eval(0.0);
            assert!((start.point - DVec2::new(10.0, 20.0)).length() < 1e-9);
            assert!((start.tangent - DVec2::from_angle(0.3)).length() < 1e-12);
            // The centre is 288 m to the side of travel; the end lies on that circle.
            let side = if length < 0.0 { -1.0 } else { 1.0 };
            let centre = start.point + start.tangent.perp() * 288.0 * side;
            let end = seg.eval(length.abs());
            assert!(((end.point - centre).length() - 288.0).abs() < 1e-9);
            // Distance along is arc length: sum of chords over fine steps.
            let n = 20_000;
            let chords: f64 = (0..n)
                .map(|i| {
                    let a = seg.eval(length.abs() * i as f64 / n as f64).point;
                    let b = seg.eval(length.abs() * (i + 1) as f64 / n as f64).point;
                    a.distance(b)
                })
                .sum();
            assert!(
                (chords - length.abs()).abs() / length.abs() < 1e-6,
                "{chords}"
            );
        }
    }

    #[test]
    fn spiral_distance_along_is_arc_length() {
        let parents = [
            Heading::Clothoid(-120.0),
            Heading::Polynomial(vec![(0, 900.0), (2, 80.0)]),
            Heading::Sine {
                constant: Some(500.0),
                linear: Some(150.0),
                sine: 300.0,
                length: 100.0,
            },
            Heading::Cosine {
                constant: None,
                cosine: 400.0,
                length: 100.0,
            },
        ];
        for h in parents {
            let n = 10_000;
            let chords: f64 = (0..n)
                .map(|i| {
                    h.point(100.0 * i as f64 / n as f64)
                        .distance(h.point(100.0 * (i + 1) as f64 / n as f64))
                })
                .sum();
            assert!((chords - 100.0).abs() / 100.0 < 1e-6, "{h:?}: {chords}");
        }
    }
}

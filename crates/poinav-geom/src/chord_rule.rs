//! How finely curved geometry that is not a circular arc (B-spline curves and surfaces, faces
//! of advanced breps) is tessellated: the crate's arc rule ([`crate::curve::MAX_ARC_STEP`])
//! restated as a ratio of sagitta to chord, so that any curve is cut as finely as a circle of
//! the same curvature would be.

use glam::DVec3;

/// Largest sagitta (distance from a chord's middle to the curve) per unit of chord length:
/// `tan(MAX_ARC_STEP / 4) / 2`, the ratio of a 5-degree chord of a circle (0.0109).
pub const MAX_SAG_RATIO: f64 = 0.010_910_038_811_074_737;

/// Sagittas below this many metres (0.01 mm) never call for a finer cut.
pub const MIN_SAG: f64 = 1e-5;

/// Deepest bisection of one initial segment (2^12 pieces).
const MAX_BISECTIONS: usize = 12;

/// True when the chord from `a` to `b` strays too far from `mid`, the curve's (or surface's)
/// point halfway between them in parameter.
pub fn too_coarse(a: DVec3, b: DVec3, mid: DVec3) -> bool {
    let sag = (mid - (a + b) / 2.0).length();
    // The margin keeps chords of exactly the arc rule's angle (rounded) from being cut.
    sag > MIN_SAG && sag > MAX_SAG_RATIO * (1.0 + 1e-6) * a.distance(b)
}

/// Parameters and points of `f` on `[t0, t1]`, first cut into `n` equal segments, each then
/// bisected while [`too_coarse`]; both ends included, in order.
pub fn sample(f: &dyn Fn(f64) -> DVec3, t0: f64, t1: f64, n: usize) -> Vec<(f64, DVec3)> {
    let n = n.max(1);
    let mut out = vec![(t0, f(t0))];
    for i in 0..n {
        let a = t0 + (t1 - t0) * i as f64 / n as f64;
        let b = if i + 1 == n {
            t1
        } else {
            t0 + (t1 - t0) * (i + 1) as f64 / n as f64
        };
        let fb = f(b);
        bisect(
            f,
            (a, out.last().expect("starts with t0").1),
            (b, fb),
            0,
            &mut out,
        );
    }
    out
}

fn bisect(
    f: &dyn Fn(f64) -> DVec3,
    a: (f64, DVec3),
    b: (f64, DVec3),
    depth: usize,
    out: &mut Vec<(f64, DVec3)>,
) {
    let tm = (a.0 + b.0) / 2.0;
    let m = f(tm);
    if depth < MAX_BISECTIONS && too_coarse(a.1, b.1, m) {
        bisect(f, a, (tm, m), depth + 1, out);
        bisect(f, (tm, m), b, depth + 1, out);
    } else {
        out.push(b);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::MAX_ARC_STEP;

    #[test]
    fn ratio_is_the_arc_rule_and_a_circle_is_cut_like_it() {
        let q = MAX_ARC_STEP / 4.0;
        assert!((MAX_SAG_RATIO - q.tan() / 2.0).abs() < 1e-15);
        // A unit circle starting from 4 segments ends with chords of at most 5 degrees
        // (bisection gives powers of two: 128 chords of 2.8 degrees).
        let f = |t: f64| DVec3::new(t.cos(), t.sin(), 0.0);
        let pts = sample(&f, 0.0, std::f64::consts::TAU, 4);
        assert_eq!(pts.len(), 129);
        assert!(pts
            .windows(2)
            .all(|w| w[1].0 - w[0].0 <= MAX_ARC_STEP + 1e-12));
        // A straight line stays one segment per initial segment.
        assert_eq!(sample(&|t| DVec3::X * t, 0.0, 10.0, 3).len(), 4);
    }
}

//! Self-crossing plane polygons: whether the rings of a polygon with holes cross themselves or
//! each other (a sweep over their edges, its work bounded), and such a polygon resolved into
//! simple areas with `i_overlay` (the outer ring filled by the non-zero rule, holes taken out).
//!
//! The ear clipper (`earcutr`) is quick on simple polygons, but on a self-crossing one with
//! thousands of points it falls back to splitting the polygon along every candidate diagonal,
//! cubic in the point count (minutes for a 4,000-point star). So a profile is checked here
//! first and resolved when it crosses itself, and [`crate::triangulation::triangulate_2d`]
//! refuses a large self-crossing polygon rather than hand it to the ear clipper (its
//! `..._resolving` variants, for faces, resolve it here first). The sweep runs along the axis
//! fewer edges span at once, so a comb of long teeth costs little whichever way it lies
//! along an axis.

use glam::DVec2;
use i_overlay::core::overlay_rule::OverlayRule;

use crate::region::{overlay_rings, Region};

/// Most pairs of edges whose x-extents overlap that one check looks at, beyond
/// [`PAIRS_PER_EDGE`] per edge (0.12 s optimised, on a shared machine, 2026-11-27): a polygon
/// needing more is [`Crossings::TooComplex`].
pub const MAX_EXTRA_PAIRS: usize = 20_000_000;

/// Pairs of edges compared per edge before [`MAX_EXTRA_PAIRS`] count: real profiles compare
/// a few per edge.
pub const PAIRS_PER_EDGE: usize = 64;

/// Most crossings a polygon may have and still be resolved: `i_overlay`'s work grows faster
/// than the crossings when many lie on one edge (unoptimised, 2 s for 20,000 crossings on
/// edges crossing 200 others each, 130 s for 125,000), so a boundary crossing itself more
/// often is [`Crossings::TooComplex`].
pub const MAX_CROSSINGS: usize = 10_000;

/// What [`crossings`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Crossings {
    /// No two edges cross or overlap (edges meeting at a shared point are fine).
    None,
    /// This many pairs of edges cross or overlap.
    Some(usize),
    /// More than [`MAX_CROSSINGS`] crossings, or more pairs to compare than the bound allows.
    TooComplex,
}

/// One edge: its ring, its index in the ring, its ends.
#[derive(Clone, Copy)]
struct Edge {
    ring: usize,
    index: usize,
    a: DVec2,
    b: DVec2,
}

impl Edge {
    fn x_range(&self) -> (f64, f64) {
        (self.a.x.min(self.b.x), self.a.x.max(self.b.x))
    }
}

/// Whether the edges of `rings` (each implicitly closed) cross or overlap one another,
/// edges that follow each other in a ring aside. Edges that only share an end are not
/// counted (a polygon's hole touching its boundary at a corner is triangulated as it is);
/// an end lying inside another edge, or edges overlapping along a line, are.
pub fn crossings(rings: &[&[DVec2]]) -> Crossings {
    count(rings, false, MAX_EXTRA_PAIRS)
}

/// Like [`crossings`], but counting only edges that cross at a point inside both (no
/// touching, no overlaps): what makes the ear clipper's work cubic.
pub fn proper_crossings(rings: &[&[DVec2]]) -> Crossings {
    count(rings, true, MAX_EXTRA_PAIRS)
}

/// The sweep: looks at no more than `extra_pairs` pairs of edges beyond [`PAIRS_PER_EDGE`]
/// per edge.
fn count(rings: &[&[DVec2]], proper_only: bool, extra_pairs: usize) -> Crossings {
    let mut edges: Vec<Edge> = Vec::new();
    for (r, ring) in rings.iter().enumerate() {
        let n = ring.len();
        for i in 0..n {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            if !(a.is_finite() && b.is_finite()) {
                return Crossings::TooComplex;
            }
            if a != b {
                edges.push(Edge {
                    ring: r,
                    index: i,
                    a,
                    b,
                });
            }
        }
    }
    // Sweep along the axis fewer edges span at once (a comb of long teeth along x is swept
    // along y): the mirror image has the same crossings.
    if sweep_along_y(&edges) {
        for e in &mut edges {
            e.a = DVec2::new(e.a.y, e.a.x);
            e.b = DVec2::new(e.b.y, e.b.x);
        }
    }
    let lens: Vec<usize> = rings.iter().map(|r| r.len()).collect();
    let adjacent = |e: &Edge, f: &Edge| {
        e.ring == f.ring && {
            let n = lens[e.ring];
            (e.index + 1) % n == f.index || (f.index + 1) % n == e.index
        }
    };
    edges.sort_by(|e, f| e.x_range().0.total_cmp(&f.x_range().0));
    let budget = extra_pairs + PAIRS_PER_EDGE * edges.len();
    let (mut pairs, mut found) = (0usize, 0usize);
    // Edges whose x-extent reaches the sweep line, dropped once it passes their end.
    let mut active: Vec<usize> = Vec::new();
    for (k, e) in edges.iter().enumerate() {
        let (x0, _) = e.x_range();
        // Every edge looked at counts, whether its y-extent overlaps or not.
        pairs += active.len();
        if pairs > budget {
            return Crossings::TooComplex;
        }
        active.retain(|&j| edges[j].x_range().1 >= x0);
        let (ey0, ey1) = (e.a.y.min(e.b.y), e.a.y.max(e.b.y));
        for &j in &active {
            let f = &edges[j];
            if f.a.y.max(f.b.y) < ey0 || f.a.y.min(f.b.y) > ey1 || adjacent(e, f) {
                continue;
            }
            if segments_cross(e.a, e.b, f.a, f.b, proper_only) {
                found += 1;
                if found > MAX_CROSSINGS {
                    return Crossings::TooComplex;
                }
            }
        }
        active.push(k);
    }
    if found == 0 {
        Crossings::None
    } else {
        Crossings::Some(found)
    }
}

/// True when a sweep line across y would meet fewer edges at once, on average, than one
/// across x: the edges' extents along y, summed, cover the polygon's height fewer times than
/// their extents along x cover its width.
fn sweep_along_y(edges: &[Edge]) -> bool {
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    let mut spans = DVec2::ZERO;
    for e in edges {
        lo = lo.min(e.a.min(e.b));
        hi = hi.max(e.a.max(e.b));
        spans += (e.b - e.a).abs();
    }
    let size = hi - lo;
    // Covered this many times over: spans.y / size.y < spans.x / size.x, without dividing.
    size.x > 0.0 && size.y > 0.0 && spans.y * size.x < spans.x * size.y
}

/// True when segments `a`-`b` and `c`-`d` cross at a point inside both, or (unless
/// `proper_only`) one's end lies inside the other or they overlap along a stretch of line;
/// false when they only share an end.
fn segments_cross(a: DVec2, b: DVec2, c: DVec2, d: DVec2, proper_only: bool) -> bool {
    let orient = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    let opposite = |s: f64, t: f64| (s > 0.0 && t < 0.0) || (s < 0.0 && t > 0.0);
    if proper_only {
        return opposite(d1, d2) && opposite(d3, d4);
    }
    if d1 == 0.0 && d2 == 0.0 && d3 == 0.0 && d4 == 0.0 {
        // On one line: they overlap when their extents along it do by more than a point.
        let axis = b - a;
        let t = |p: DVec2| (p - a).dot(axis);
        let (c0, c1) = (t(c).min(t(d)), t(c).max(t(d)));
        return c0.max(0.0) < c1.min(axis.length_squared());
    }
    if opposite(d1, d2) && opposite(d3, d4) {
        return true;
    }
    // Strictly inside the segment p-q (p, q and r on one line).
    let inside = |p: DVec2, q: DVec2, r: DVec2| {
        let t = (r - p).dot(q - p);
        t > 0.0 && t < (q - p).length_squared()
    };
    (d1 == 0.0 && inside(c, d, a))
        || (d2 == 0.0 && inside(c, d, b))
        || (d3 == 0.0 && inside(a, b, c))
        || (d4 == 0.0 && inside(a, b, d))
}

/// The simple areas a self-crossing polygon encloses: `outer` filled by the non-zero rule
/// (a part it winds around twice counts once, a loop turning the other way counts too), less
/// `holes` (each filled the same way). Outer rings come out counter-clockwise, holes
/// clockwise.
pub fn resolve(outer: &[DVec2], holes: &[Vec<DVec2>]) -> Vec<Region> {
    let contour = |r: &[DVec2]| r.iter().map(|p| [p.x, p.y]).collect::<Vec<[f64; 2]>>();
    let subject = [contour(outer)];
    let clip: Vec<Vec<[f64; 2]>> = holes.iter().map(|h| contour(h)).collect();
    let rule = if clip.is_empty() {
        OverlayRule::Subject
    } else {
        OverlayRule::Difference
    };
    overlay_rings(&subject, &clip, rule)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::region::total_area;

    /// The star polygon {n/k}: n points on the unit circle, each joined to the k-th next.
    pub(crate) fn star(n: usize, k: usize) -> Vec<DVec2> {
        (0..n)
            .map(|i| DVec2::from_angle(std::f64::consts::TAU * (i * k % n) as f64 / n as f64))
            .collect()
    }

    #[test]
    fn a_pentagram_crosses_itself_five_times_and_fills_whole() {
        let p = star(5, 2);
        assert_eq!(crossings(&[&p]), Crossings::Some(5));
        let r = resolve(&p, &[]);
        assert_eq!(r.len(), 1);
        assert_eq!(r[0].outer.len(), 10);
        // The whole star: the inner pentagon and five tips, 1.1226 for a unit circumradius.
        let (c36, s36) = (36f64.to_radians().cos(), 36f64.to_radians().sin());
        let ri = 72f64.to_radians().cos() / c36;
        let pentagon = 2.5 * ri * ri * 72f64.to_radians().sin();
        let tips = 5.0 * 0.5 * (2.0 * ri * s36) * (1.0 - ri * c36);
        assert!((pentagon + tips - 1.122_570).abs() < 1e-6);
        assert!(
            (total_area(&r) - pentagon - tips).abs() < 1e-6,
            "{}",
            total_area(&r)
        );
    }

    #[test]
    fn simple_rings_and_touching_holes_do_not_cross() {
        let sq = |x0: f64, y0: f64, s: f64| {
            vec![
                DVec2::new(x0, y0),
                DVec2::new(x0 + s, y0),
                DVec2::new(x0 + s, y0 + s),
                DVec2::new(x0, y0 + s),
            ]
        };
        let outer = sq(0.0, 0.0, 4.0);
        let circle = star(400, 1);
        assert_eq!(crossings(&[&outer, &sq(1.0, 1.0, 1.0)]), Crossings::None);
        assert_eq!(crossings(&[&circle]), Crossings::None);
        // A hole in the outer ring's corner runs along two of its sides (2 overlaps) and ends
        // on them (2 ends inside an edge); one meeting the corner at a point only touches it.
        assert_eq!(crossings(&[&outer, &sq(0.0, 0.0, 1.0)]), Crossings::Some(4));
        assert_eq!(crossings(&[&outer, &sq(3.0, 3.0, 1.0)]), Crossings::Some(4));
        let corner = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 0.5),
        ];
        assert_eq!(crossings(&[&outer, &corner]), Crossings::None);
        // A ring run twice over (its edges lie on each other, end to end).
        let twice: Vec<DVec2> = outer.iter().chain(&outer).copied().collect();
        assert_eq!(crossings(&[&twice]), Crossings::Some(4));
        // Touching and overlapping are not crossing properly.
        assert_eq!(proper_crossings(&[&twice]), Crossings::None);
        assert_eq!(
            proper_crossings(&[&outer, &sq(0.0, 0.0, 1.0)]),
            Crossings::None
        );
        // A hole reaching out of the outer ring crosses it twice; resolved, it is cut away.
        let out = sq(3.0, 1.0, 2.0);
        assert_eq!(crossings(&[&outer, &out]), Crossings::Some(2));
        assert_eq!(proper_crossings(&[&outer, &out]), Crossings::Some(2));
        let r = resolve(&outer, &[out]);
        assert!((total_area(&r) - (16.0 - 2.0)).abs() < 1e-6);
    }

    #[test]
    fn a_4001_point_star_is_resolved_into_its_disc() {
        // Each chord {4001/2} crosses its two neighbours: 4,001 crossings; filled by the
        // non-zero rule, the inside is the regular 4001-gon (nearly pi) less a notch between
        // each two points (down to where the chords from them cross), 2e-6 in all.
        let n = 4001;
        let p = star(n, 2);
        assert_eq!(crossings(&[&p]), Crossings::Some(n));
        let r = resolve(&p, &[]);
        assert_eq!(r.len(), 1);
        let regular = n as f64 / 2.0 * (std::f64::consts::TAU / n as f64).sin();
        let notches = regular - total_area(&r);
        assert!(notches > 0.0 && notches < 3e-6, "{}", total_area(&r));
        // {n/(n-1)/2}: every chord crosses nearly every other, far past the bound.
        assert_eq!(crossings(&[&star(2001, 1000)]), Crossings::TooComplex);
    }

    #[test]
    fn a_comb_of_long_teeth_costs_the_bound_not_quadratic_time() {
        // Teeth 100 m long and 1 cm apart on a spine: every edge's x-extent overlaps every
        // other's, so the sweep goes along y, where none overlap: 1,000 teeth are checked
        // within a bound of a million pairs. Turned by 45 degrees, every edge's extent
        // overlaps every other's along both axes: 100 teeth are checked (no crossing);
        // 1,000, some 8 million pairs to look at, stop at the bound (the real one is 20
        // million).
        let comb = |teeth: usize, turn: f64| {
            let top = teeth as f64 * 0.01;
            let mut c = vec![DVec2::new(-1.0, top), DVec2::new(-1.0, 0.0)];
            for i in 0..teeth {
                let y = i as f64 * 0.01;
                c.extend(
                    [(0.0, y), (100.0, y), (100.0, y + 0.005), (0.0, y + 0.005)].map(DVec2::from),
                );
            }
            let r = DVec2::from_angle(turn);
            c.into_iter().map(|p| r.rotate(p)).collect::<Vec<_>>()
        };
        let diagonal = std::f64::consts::FRAC_PI_4;
        assert_eq!(
            count(&[&comb(1000, 0.0)], false, 1_000_000),
            Crossings::None
        );
        assert_eq!(
            count(&[&comb(100, diagonal)], false, 1_000_000),
            Crossings::None
        );
        assert_eq!(
            count(&[&comb(1000, diagonal)], false, 1_000_000),
            Crossings::TooComplex
        );
        assert_eq!(crossings(&[&comb(100, diagonal)]), Crossings::None);
    }
}

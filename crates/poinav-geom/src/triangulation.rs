//! Triangulation of plane polygons with holes (ear clipping by `earcutr`): profile caps in 2D
//! and polygonal faces in 3D (projected on their best-fitting plane, Newell's normal); faces
//! whose boundaries cross are first resolved into simple areas ([`triangulate_3d_resolving`]).

use glam::{DVec2, DVec3};
use rustc_hash::FxHashMap;

use crate::self_crossing::{proper_crossings, resolve, Crossings};

/// Most points one polygon (outer boundary and holes together) may have.
pub const MAX_POLYGON_POINTS: usize = 1 << 20;

/// Polygons with more points than this are checked for self-crossings before the ear clipper
/// sees them: on a self-crossing polygon its work grows with the cube of the point count (a
/// few milliseconds at this size, minutes at 4,000 points).
pub const CROSSING_CHECK_ABOVE: usize = 128;

/// Triangles of the polygon `outer` with `holes`, as indices into the points of `outer`
/// followed by those of each hole, counter-clockwise in the plane, every point used (see
/// [`restore_skipped`]). `None` when the polygon
/// cannot be triangulated (fewer than three points, too many points, a numeric failure, or
/// more than [`CROSSING_CHECK_ABOVE`] points and edges that cross: profiles are resolved
/// before, in [`crate::profile`]).
pub fn triangulate_2d(outer: &[DVec2], holes: &[Vec<DVec2>]) -> Option<Vec<[u32; 3]>> {
    let n = outer.len() + holes.iter().map(Vec::len).sum::<usize>();
    if outer.len() < 3 || n > MAX_POLYGON_POINTS {
        return None;
    }
    if n > CROSSING_CHECK_ABOVE {
        let rings: Vec<&[DVec2]> = std::iter::once(outer)
            .chain(holes.iter().map(Vec::as_slice))
            .collect();
        // Rings that only touch or overlap are clipped as they come (a keyhole is what the
        // ear clipper makes of a hole itself).
        if proper_crossings(&rings) != Crossings::None {
            return None;
        }
    }
    earcut(outer, holes)
}

/// [`triangulate_2d`] of a polygon known to be simple (or small), without the check.
fn earcut(outer: &[DVec2], holes: &[Vec<DVec2>]) -> Option<Vec<[u32; 3]>> {
    let n = outer.len() + holes.iter().map(Vec::len).sum::<usize>();
    if outer.len() < 3 || n > MAX_POLYGON_POINTS {
        return None;
    }
    let points: Vec<DVec2> = outer
        .iter()
        .chain(holes.iter().flatten())
        .copied()
        .collect();
    if outer.len() == 3 && holes.is_empty() {
        return Some(vec![ccw(&points, [0, 1, 2])]);
    }
    if outer.len() == 4 && holes.is_empty() && convex_quad(outer) {
        return Some(vec![ccw(&points, [0, 1, 2]), ccw(&points, [0, 2, 3])]);
    }
    // Shift to the first point: large coordinates lose no precision.
    let o = points[0];
    let mut flat = Vec::with_capacity(2 * n);
    for p in &points {
        flat.push(p.x - o.x);
        flat.push(p.y - o.y);
    }
    let mut starts = Vec::with_capacity(holes.len());
    let mut at = outer.len();
    for h in holes.iter().filter(|h| !h.is_empty()) {
        starts.push(at);
        at += h.len();
    }
    let indices = earcutr::earcut(&flat, &starts, 2).ok()?;
    let mut tris: Vec<[u32; 3]> = indices
        .chunks_exact(3)
        .map(|t| ccw(&points, [t[0] as u32, t[1] as u32, t[2] as u32]))
        .collect();
    let lengths: Vec<usize> = std::iter::once(outer.len())
        .chain(holes.iter().map(Vec::len))
        .collect();
    restore_skipped(&mut tris, &lengths);
    Some(tris)
}

/// The triangle with its corners ordered counter-clockwise.
fn ccw(points: &[DVec2], t: [u32; 3]) -> [u32; 3] {
    let [a, b, c] = t.map(|i| points[i as usize]);
    if (b - a).perp_dot(c - a) < 0.0 {
        [t[0], t[2], t[1]]
    } else {
        t
    }
}

/// True when the quadrilateral turns the same way at every corner.
fn convex_quad(q: &[DVec2]) -> bool {
    let turn = |i: usize| (q[(i + 1) % 4] - q[i]).perp_dot(q[(i + 2) % 4] - q[(i + 1) % 4]);
    let t: Vec<f64> = (0..4).map(turn).collect();
    t.iter().all(|&x| x > 0.0) || t.iter().all(|&x| x < 0.0)
}

/// Newell's normal of a closed 3D polygon (not normalised; its length is twice the area).
pub fn newell_normal(points: &[DVec3]) -> DVec3 {
    let Some(&o) = points.first() else {
        return DVec3::ZERO;
    };
    let n = points.len();
    (0..n)
        .map(|i| (points[i] - o).cross(points[(i + 1) % n] - o))
        .sum()
}

/// Triangles of a plane 3D polygon `outer` with `holes` (indices as in [`triangulate_2d`]),
/// facing the side its outer boundary turns counter-clockwise around (Newell's normal).
/// `None` when the polygon has no area or cannot be triangulated.
pub fn triangulate_3d(outer: &[DVec3], holes: &[Vec<DVec3>]) -> Option<Vec<[u32; 3]>> {
    let normal = newell_normal(outer).try_normalize()?;
    if outer.len() == 3 && holes.is_empty() {
        return Some(vec![[0, 1, 2]]);
    }
    let (_, outer2, holes2) = in_plane(normal, outer, holes);
    triangulate_2d(&outer2, &holes2)
}

/// A right-handed frame `(u, v)` of the plane with unit `normal` (counter-clockwise in
/// (u, v) faces the normal), and `outer` and `holes` in it.
fn in_plane(
    normal: DVec3,
    outer: &[DVec3],
    holes: &[Vec<DVec3>],
) -> ((DVec3, DVec3), Vec<DVec2>, Vec<Vec<DVec2>>) {
    let u = normal.any_orthonormal_vector();
    let v = normal.cross(u);
    let project = |p: &DVec3| DVec2::new(p.dot(u), p.dot(v));
    let outer2 = outer.iter().map(project).collect();
    let holes2 = holes
        .iter()
        .map(|h| h.iter().map(project).collect())
        .collect();
    ((u, v), outer2, holes2)
}

/// Like [`triangulate_2d`], but a polygon of more than [`CROSSING_CHECK_ABOVE`] points whose
/// rings cross is resolved into the simple areas it encloses first (non-zero rule, holes taken
/// out, as [`crate::profile`] resolves profiles) instead of refused. Returns the points the
/// resolution adds (crossings; indices from the polygon's point count on) and the triangles.
/// `None` as for [`triangulate_2d`], and when the rings cross too often to be resolved
/// ([`Crossings::TooComplex`]).
///
/// Points of the areas that are points of the polygon (within a millionth of its size, what
/// `i_overlay`'s integer grid moves them) keep their index, so neighbouring faces still share
/// them.
pub fn triangulate_2d_resolving(
    outer: &[DVec2],
    holes: &[Vec<DVec2>],
) -> Option<(Vec<DVec2>, Vec<[u32; 3]>)> {
    let n = outer.len() + holes.iter().map(Vec::len).sum::<usize>();
    if outer.len() < 3 || n > MAX_POLYGON_POINTS {
        return None;
    }
    if n <= CROSSING_CHECK_ABOVE {
        return earcut(outer, holes).map(|t| (Vec::new(), t));
    }
    let rings: Vec<&[DVec2]> = std::iter::once(outer)
        .chain(holes.iter().map(Vec::as_slice))
        .collect();
    match proper_crossings(&rings) {
        Crossings::None => earcut(outer, holes).map(|t| (Vec::new(), t)),
        Crossings::TooComplex => None,
        Crossings::Some(_) => Some(resolved(outer, holes)),
    }
}

/// The areas of a self-crossing polygon, triangulated: (added points, triangles).
fn resolved(outer: &[DVec2], holes: &[Vec<DVec2>]) -> (Vec<DVec2>, Vec<[u32; 3]>) {
    let input: Vec<DVec2> = outer
        .iter()
        .chain(holes.iter().flatten())
        .copied()
        .collect();
    let (lo, hi) = crate::polygon::bounds(&input).unwrap_or_default();
    let cell = ((hi - lo).max_element() * 1e-6).max(f64::MIN_POSITIVE);
    let key = |p: DVec2| (((p.x - lo.x) / cell) as i64, ((p.y - lo.y) / cell) as i64);
    let mut grid: FxHashMap<(i64, i64), Vec<u32>> = FxHashMap::default();
    for (i, p) in input.iter().enumerate() {
        grid.entry(key(*p)).or_default().push(i as u32);
    }
    let mut added: Vec<DVec2> = Vec::new();
    let mut index_of = |p: DVec2| -> u32 {
        let (kx, ky) = key(p);
        let mut best: Option<(f64, u32)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for &i in grid.get(&(kx + dx, ky + dy)).into_iter().flatten() {
                    let d = input[i as usize].distance(p);
                    if d <= cell && best.is_none_or(|b| d < b.0) {
                        best = Some((d, i));
                    }
                }
            }
        }
        match best {
            Some((_, i)) => i,
            None => {
                added.push(p);
                (input.len() + added.len() - 1) as u32
            }
        }
    };
    let mut tris = Vec::new();
    for region in resolve(outer, holes) {
        let Some(local) = earcut(&region.outer, &region.holes) else {
            continue;
        };
        let global: Vec<u32> = region
            .outer
            .iter()
            .chain(region.holes.iter().flatten())
            .map(|p| index_of(*p))
            .collect();
        tris.extend(
            local
                .iter()
                .map(|t| t.map(|i| global[i as usize]))
                .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]),
        );
    }
    (added, tris)
}

/// [`triangulate_3d`] through [`triangulate_2d_resolving`]: a face whose bounds cross is
/// resolved into the simple areas it encloses. Returns the points it adds (on the face's
/// plane; indices from the face's point count on) and the triangles.
pub fn triangulate_3d_resolving(
    outer: &[DVec3],
    holes: &[Vec<DVec3>],
) -> Option<(Vec<DVec3>, Vec<[u32; 3]>)> {
    let normal = newell_normal(outer).try_normalize()?;
    if outer.len() == 3 && holes.is_empty() {
        return Some((Vec::new(), vec![[0, 1, 2]]));
    }
    let ((u, v), outer2, holes2) = in_plane(normal, outer, holes);
    let (added, tris) = triangulate_2d_resolving(&outer2, &holes2)?;
    let height = outer.iter().map(|p| p.dot(normal)).sum::<f64>() / outer.len() as f64;
    let added = added
        .iter()
        .map(|q| u * q.x + v * q.y + normal * height)
        .collect();
    Some((added, tris))
}

/// Puts back into `tris` the boundary points the ear clipper left out (it drops points that
/// lie on a straight line between their neighbours): each run of left-out points of a ring
/// (`ring_lengths` give the rings in index order) becomes a fan in the triangle that spans
/// it, so that a neighbouring face sharing those points (an extrusion's side, the next face
/// of a brep) meets this one without cracks. [`triangulate_2d`] does this for every caller.
pub fn restore_skipped(tris: &mut Vec<[u32; 3]>, ring_lengths: &[usize]) {
    let n: usize = ring_lengths.iter().sum();
    let mut used = vec![false; n];
    for t in tris.iter() {
        for &i in t {
            if let Some(u) = used.get_mut(i as usize) {
                *u = true;
            }
        }
    }
    if used.iter().all(|&u| u) {
        return;
    }
    // Directed edge -> its triangle, kept up to date as fans replace triangles.
    let mut edges: FxHashMap<(u32, u32), usize> = FxHashMap::default();
    for (ti, t) in tris.iter().enumerate() {
        for k in 0..3 {
            edges.insert((t[k], t[(k + 1) % 3]), ti);
        }
    }
    let mut start = 0;
    for &len in ring_lengths {
        let ring: Vec<u32> = (start..start + len).map(|i| i as u32).collect();
        start += len;
        let Some(first) = (0..len).find(|&k| used[ring[k] as usize]) else {
            continue;
        };
        // Walk the ring from a used point; collect runs of unused points between used ones.
        let mut k = first;
        for _ in 0..len {
            let a = ring[k];
            let mut run = Vec::new();
            let mut j = (k + 1) % len;
            while !used[ring[j] as usize] {
                run.push(ring[j]);
                j = (j + 1) % len;
            }
            let b = ring[j];
            if !run.is_empty() {
                fan_in(tris, &mut edges, a, b, &run);
            }
            k = j;
            if k == first {
                break;
            }
        }
    }
}

/// Replaces the triangle with edge a-b by a fan through `run` (the points between a and b).
fn fan_in(
    tris: &mut Vec<[u32; 3]>,
    edges: &mut FxHashMap<(u32, u32), usize>,
    a: u32,
    b: u32,
    run: &[u32],
) {
    let (ti, chain): (usize, Vec<u32>) = if let Some(&ti) = edges.get(&(a, b)) {
        let chain = std::iter::once(a).chain(run.iter().copied()).chain([b]);
        (ti, chain.collect())
    } else if let Some(&ti) = edges.get(&(b, a)) {
        let chain = std::iter::once(b)
            .chain(run.iter().rev().copied())
            .chain([a]);
        (ti, chain.collect())
    } else {
        return;
    };
    let t = tris[ti];
    let (x, y) = (chain[0], chain[chain.len() - 1]);
    let Some(k) = (0..3).find(|&k| (t[k], t[(k + 1) % 3]) == (x, y)) else {
        return;
    };
    let c = t[(k + 2) % 3];
    for k in 0..3 {
        edges.remove(&(t[k], t[(k + 1) % 3]));
    }
    let mut put = |tris: &mut Vec<[u32; 3]>, at: usize, t: [u32; 3]| {
        if at == tris.len() {
            tris.push(t);
        } else {
            tris[at] = t;
        }
        for k in 0..3 {
            edges.insert((t[k], t[(k + 1) % 3]), at);
        }
    };
    put(tris, ti, [chain[0], chain[1], c]);
    for w in chain[1..].windows(2) {
        let at = tris.len();
        put(tris, at, [w[0], w[1], c]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(points: &[DVec2], tris: &[[u32; 3]]) -> f64 {
        tris.iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| points[i as usize]);
                (b - a).perp_dot(c - a) / 2.0
            })
            .sum()
    }

    #[test]
    fn square_with_a_square_hole() {
        let outer = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(4.0, 0.0),
            DVec2::new(4.0, 4.0),
            DVec2::new(0.0, 4.0),
        ];
        let hole = vec![
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 2.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(2.0, 1.0),
        ];
        let tris = triangulate_2d(&outer, std::slice::from_ref(&hole)).unwrap();
        let all: Vec<DVec2> = outer.iter().chain(&hole).copied().collect();
        assert_eq!(tris.len(), 8);
        assert!((area(&all, &tris) - 15.0).abs() < 1e-12);
    }

    #[test]
    fn points_on_straight_runs_are_kept() {
        // A 4 x 1 rectangle with three extra points on its bottom edge and one on its top.
        let outer: Vec<DVec2> = [
            (0., 0.),
            (1., 0.),
            (2., 0.),
            (3., 0.),
            (4., 0.),
            (4., 1.),
            (2., 1.),
            (0., 1.),
        ]
        .iter()
        .map(|&(x, y)| DVec2::new(x, y))
        .collect();
        // As the ear clipper may leave them out: one triangle over the whole bottom edge.
        let mut tris = vec![[0, 4, 5], [0, 5, 7]];
        restore_skipped(&mut tris, &[outer.len()]);
        let mut used: Vec<u32> = tris.iter().flatten().copied().collect();
        used.sort();
        used.dedup();
        assert_eq!(used, (0..8).collect::<Vec<u32>>());
        assert!((area(&outer, &tris) - 4.0).abs() < 1e-12);
        assert!(tris.iter().all(|t| {
            let [a, b, c] = t.map(|i| outer[i as usize]);
            (b - a).perp_dot(c - a) > 0.0
        }));
    }

    #[test]
    fn face_in_3d_faces_its_newell_normal() {
        // An L-shaped face in the plane x = 5, turning counter-clockwise seen from +x.
        let pts: Vec<DVec3> = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)]
            .iter()
            .map(|&(y, z)| DVec3::new(5.0, y, z))
            .collect();
        let tris = triangulate_3d(&pts, &[]).unwrap();
        assert_eq!(tris.len(), 4);
        let mut normal = DVec3::ZERO;
        for t in tris {
            let [a, b, c] = t.map(|i| pts[i as usize]);
            normal += (b - a).cross(c - a) / 2.0;
        }
        assert!(
            (normal - DVec3::new(3.0, 0.0, 0.0)).length() < 1e-12,
            "{normal}"
        );
        assert!(triangulate_3d(&pts[..2], &[]).is_none());
    }

    #[test]
    fn a_large_self_crossing_polygon_is_refused_not_clipped() {
        // 1,000 points alternately on either side of the centre: every edge crosses most
        // others. The ear clipper takes about a minute on it (unoptimised); it is refused.
        let asterisk: Vec<DVec2> = (0..1000)
            .map(|i| {
                let side = if i % 2 == 0 { 1.0 } else { -1.0 };
                DVec2::from_angle(std::f64::consts::TAU * i as f64 / 1000.0) * side
            })
            .collect();
        assert!(triangulate_2d(&asterisk, &[]).is_none());
        // Small ones are still clipped as they come.
        assert_eq!(
            triangulate_2d(&asterisk[..100], &[]).map(|t| t.len()),
            Some(49)
        );
        // A large simple polygon is not refused: a 1,000-gon gives 998 triangles.
        let circle: Vec<DVec2> = (0..1000)
            .map(|i| DVec2::from_angle(std::f64::consts::TAU * i as f64 / 1000.0))
            .collect();
        assert_eq!(triangulate_2d(&circle, &[]).map(|t| t.len()), Some(998));
        // Resolving does not help a tangle of 250,000 crossings: refused too.
        assert!(triangulate_2d_resolving(&asterisk, &[]).is_none());
    }

    /// A comb: a spine 1 m wide, `teeth` teeth 100 m long, 5 mm thick, 1 cm apart (4 points
    /// each, 2 for the spine); simple, its area the spine's (a trapezoid: the last edge
    /// runs back to the spine's top) and the teeth's. (IfcOpenShell 0.9 meshes the one of
    /// 1,249 teeth as a face to 636.9875 m2, this value, in 110 s.)
    fn comb(teeth: usize) -> (Vec<DVec2>, f64) {
        let top = teeth as f64 * 0.01;
        let mut c = vec![DVec2::new(-1.0, top), DVec2::new(-1.0, 0.0)];
        for i in 0..teeth {
            let y = i as f64 * 0.01;
            c.extend([(0.0, y), (100.0, y), (100.0, y + 0.005), (0.0, y + 0.005)].map(DVec2::from));
        }
        (c, top - 0.0025 + teeth as f64 * 0.5)
    }

    #[test]
    fn large_simple_and_self_crossing_faces_are_triangulated() {
        // Simple combs of 5,002 and 8,002 points (the latter past the crossing check's pair
        // bound when swept along x: every tooth spans the width): all of their area.
        for teeth in [1250, 2000] {
            let (c, expected) = comb(teeth);
            let (added, tris) = triangulate_2d_resolving(&c, &[]).unwrap();
            assert!(added.is_empty());
            assert!(
                (area(&c, &tris) - expected).abs() < 1e-6,
                "{teeth}: {}",
                area(&c, &tris)
            );
        }
        // A star of 401 points drawn in one stroke ({401/2}, every chord crossing its two
        // neighbours) as a 3D face tilted about x: resolved into the 401-gon less its
        // notches, the crossings added as points on the face's plane.
        let n = 401;
        let star: Vec<DVec3> = (0..n)
            .map(|i| {
                let p = DVec2::from_angle(std::f64::consts::TAU * (2 * i % n) as f64 / n as f64);
                DVec3::new(p.x, p.y * 0.6, p.y * 0.8 + 2.0)
            })
            .collect();
        let (added, tris) = triangulate_3d_resolving(&star, &[]).unwrap();
        assert_eq!(added.len(), n);
        let pts: Vec<DVec3> = star.iter().chain(&added).copied().collect();
        for p in &added {
            assert!(
                (p.y * 0.8 - (p.z - 2.0) * 0.6).abs() < 1e-12,
                "{p} off the plane"
            );
        }
        let a: f64 = tris
            .iter()
            .map(|t| {
                (pts[t[1] as usize] - pts[t[0] as usize])
                    .cross(pts[t[2] as usize] - pts[t[0] as usize])
                    .length()
                    / 2.0
            })
            .sum();
        let regular = n as f64 / 2.0 * (std::f64::consts::TAU / n as f64).sin();
        assert!(a < regular && regular - a < 1e-3, "{a} vs {regular}");
    }
}

//! Triangulating a curved face in its (u, v) parameters once its bounds are triangulated:
//! grid points of its surface put in ([`Surface::grid`]), Lawson's flips to a Delaunay
//! triangulation (bounds kept) in (u, v) scaled by the surface's speeds, slivers along
//! straight bounds flipped away, then red-green refinement: every inner edge whose surface
//! point halfway strays from the chord more than the chord rule allows, or across which the
//! surface turns by more than the arc rule, is split with its neighbours, until none is.

use rustc_hash::FxHashMap;

use glam::{DVec2, DVec3};

use crate::chord_rule::{MAX_SAG_RATIO, MIN_SAG};
use crate::curve::MAX_ARC_STEP;
use crate::surface::Surface;

/// How much coarser than the arc rule an inner edge of a curved face may be: a grid cell's
/// diagonal (cells of [`Surface::grid`] follow the arc rule along u and v).
const INNER_SLACK: f64 = std::f64::consts::SQRT_2;

/// Most refinement passes over one face.
const MAX_PASSES: usize = 16;

/// Triangles in (u, v) whose doubled area is at most this fraction of their longest edge
/// squared are slivers (see [`refine`]).
const SLIVER: f64 = 1e-9;

/// Most triangles one curved face may be refined into.
pub const MAX_FACE_TRIANGLES: usize = 200_000;

/// The key of the undirected edge a-b.
pub(crate) fn edge_key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// The triangles of a face on `surf` whose bounds' triangulation is `tris` (indices into
/// `uv` and `xyz`, which grow by the points put in; edges in `boundary` are the bounds):
/// seeded, made Delaunay, rid of slivers and refined. `None` past [`MAX_FACE_TRIANGLES`].
pub(crate) fn triangulate(
    surf: &Surface,
    uv: &mut Vec<DVec2>,
    xyz: &mut Vec<DVec3>,
    mut tris: Vec<[u32; 3]>,
    boundary: &rustc_hash::FxHashSet<(u32, u32)>,
) -> Option<Vec<[u32; 3]>> {
    insert_grid(surf, uv, xyz, &mut tris, boundary);
    delaunay_flips(surf, uv, &mut tris, boundary);
    flip_slivers(uv, &mut tris, boundary);
    refine(surf, uv, xyz, tris, boundary)
}

/// Makes the triangulation Delaunay (Lawson's edge flips, bounds kept) in (u, v) scaled by
/// the surface's speeds at the middle of the face, so that the triangles the ear clipper
/// strings between far-apart points of the bounds (across a whole cylinder) become ones
/// between near points, which the refinement then leaves as they are where the surface is
/// straight (along a cylinder's axis).
fn delaunay_flips(
    surf: &Surface,
    uv: &[DVec2],
    tris: &mut [[u32; 3]],
    boundary: &rustc_hash::FxHashSet<(u32, u32)>,
) {
    let (lo, hi) = uv.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let mid = (lo + hi) / 2.0;
    let h = ((hi - lo) * 1e-4).max(DVec2::splat(1e-9));
    let speed = |d: DVec2| {
        let v = surf.point(mid + d).distance(surf.point(mid - d)) / (2.0 * d.length());
        if v.is_finite() && v > 0.0 {
            v
        } else {
            1.0
        }
    };
    let scale = DVec2::new(speed(DVec2::new(h.x, 0.0)), speed(DVec2::new(0.0, h.y)));
    let p: Vec<DVec2> = uv.iter().map(|q| (*q - mid) * scale).collect();
    let ccw = |t: [u32; 3]| {
        let [a, b, c] = t.map(|i| p[i as usize]);
        (b - a).perp_dot(c - a) > 0.0
    };
    // d strictly inside the circle through the counter-clockwise a, b, c.
    let in_circle = |a: DVec2, b: DVec2, c: DVec2, d: DVec2| {
        let (a, b, c) = (a - d, b - d, c - d);
        let det = a.length_squared() * b.perp_dot(c) - b.length_squared() * a.perp_dot(c)
            + c.length_squared() * a.perp_dot(b);
        det > 1e-12 * (a.length_squared() + b.length_squared() + c.length_squared()).powi(2)
    };
    let mut by_edge: FxHashMap<(u32, u32), Vec<usize>> = FxHashMap::default();
    for (i, t) in tris.iter().enumerate() {
        for k in 0..3 {
            by_edge
                .entry(edge_key(t[k], t[(k + 1) % 3]))
                .or_default()
                .push(i);
        }
    }
    let mut stack: Vec<(u32, u32)> = by_edge.keys().copied().collect();
    stack.sort_unstable();
    let mut budget = 16 * tris.len() + 1024;
    while let Some(key) = stack.pop() {
        if budget == 0 {
            break;
        }
        if boundary.contains(&key) {
            continue;
        }
        let Some(&[ti, tj]) = by_edge.get(&key).map(|v| &v[..]) else {
            continue;
        };
        let t = tris[ti];
        let Some(k) = (0..3).find(|&k| edge_key(t[k], t[(k + 1) % 3]) == key) else {
            continue;
        };
        let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
        let Some(&d) = tris[tj].iter().find(|&&v| v != a && v != b) else {
            continue;
        };
        let [pa, pb, pc, pd] = [a, b, c, d].map(|i| p[i as usize]);
        if !ccw(t) || !in_circle(pa, pb, pc, pd) {
            continue;
        }
        let (n1, n2) = ([a, d, c], [d, b, c]);
        if !(ccw(n1) && ccw(n2)) || by_edge.contains_key(&edge_key(c, d)) {
            continue;
        }
        budget -= 1;
        tris[ti] = n1;
        tris[tj] = n2;
        by_edge.remove(&key);
        by_edge.insert(edge_key(c, d), vec![ti, tj]);
        let mut moved = |e: (u32, u32), from: usize, to: usize| {
            if let Some(v) = by_edge.get_mut(&e) {
                for x in v.iter_mut().filter(|x| **x == from) {
                    *x = to;
                }
            }
        };
        moved(edge_key(a, d), tj, ti);
        moved(edge_key(b, c), ti, tj);
        stack.extend([
            edge_key(a, d),
            edge_key(d, b),
            edge_key(b, c),
            edge_key(c, a),
        ]);
    }
}

/// Most inner grid points one face gets.
const MAX_GRID_POINTS: usize = 20_000;

/// Puts the points of `surf`'s parameter grid ([`Surface::grid`]) that lie inside the
/// face, and no nearer a bound than a third of the grid's step, into the triangulation:
/// each splits the triangle holding it in three (Delaunay flips follow), so that the
/// triangles start at about the size the surface needs instead of spanning the face.
fn insert_grid(
    surf: &Surface,
    uv: &mut Vec<DVec2>,
    xyz: &mut Vec<DVec3>,
    tris: &mut Vec<[u32; 3]>,
    boundary: &rustc_hash::FxHashSet<(u32, u32)>,
) {
    let (lo, hi) = uv.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let [us, vs] = surf.grid(lo, hi);
    if tris.is_empty() || us.is_empty() || vs.is_empty() || us.len() * vs.len() > MAX_GRID_POINTS {
        return;
    }
    let step = |l: &[f64], span: f64| {
        l.windows(2)
            .map(|w| w[1] - w[0])
            .fold(span, f64::min)
            .max(1e-12)
    };
    let scale = DVec2::new(1.0 / step(&us, hi.x - lo.x), 1.0 / step(&vs, hi.y - lo.y));
    let segments: Vec<(DVec2, DVec2)> = boundary
        .iter()
        .map(|&(a, b)| (uv[a as usize] * scale, uv[b as usize] * scale))
        .collect();
    // Segments by the unit cells (of the scaled grid) their box, grown by a third, covers.
    let cell = |x: f64| x.floor() as i64;
    let mut cells: FxHashMap<(i64, i64), Vec<usize>> = FxHashMap::default();
    for (i, &(a, b)) in segments.iter().enumerate() {
        let (lo, hi) = (a.min(b) - 1.0 / 3.0, a.max(b) + 1.0 / 3.0);
        if (hi - lo).max_element() > 1e4 {
            return;
        }
        for x in cell(lo.x)..=cell(hi.x) {
            for y in cell(lo.y)..=cell(hi.y) {
                cells.entry((x, y)).or_default().push(i);
            }
        }
    }
    let near_bound = |p: DVec2| {
        cells.get(&(cell(p.x), cell(p.y))).is_some_and(|list| {
            list.iter().any(|&i| {
                let (a, b) = segments[i];
                let (a, d) = (a - p, b - a);
                let t = (-a.dot(d) / d.length_squared().max(1e-300)).clamp(0.0, 1.0);
                (a + d * t).length() < 1.0 / 3.0
            })
        })
    };
    let mut by_edge: FxHashMap<(u32, u32), Vec<usize>> = FxHashMap::default();
    for (i, t) in tris.iter().enumerate() {
        for k in 0..3 {
            by_edge
                .entry(edge_key(t[k], t[(k + 1) % 3]))
                .or_default()
                .push(i);
        }
    }
    let strictly_inside = |t: [u32; 3], p: DVec2, uv: &[DVec2]| {
        let [a, b, c] = t.map(|i| uv[i as usize]);
        let area = (b - a).perp_dot(c - a);
        area > 0.0
            && [(a, b), (b, c), (c, a)]
                .iter()
                .all(|(x, y)| (*y - *x).perp_dot(p - *x) > 1e-9 * area)
    };
    let mut last = 0;
    for &u in &us {
        for &v in &vs {
            let p = DVec2::new(u, v);
            if near_bound(p * scale) {
                continue;
            }
            // Walk from the last triangle split towards p, across the edge p lies beyond.
            let mut ti = last.min(tris.len() - 1);
            let mut found = None;
            for step in 0..tris.len() {
                let t = tris[ti];
                // Edges tried from a turning start (a stochastic walk cannot cycle for ever).
                let beyond = (0..3).map(|k| (k + step * 7 / 3) % 3).find(|&k| {
                    let (x, y) = (uv[t[k] as usize], uv[t[(k + 1) % 3] as usize]);
                    (y - x).perp_dot(p - x) < 0.0
                });
                let Some(k) = beyond else {
                    found = Some(ti);
                    break;
                };
                let key = edge_key(t[k], t[(k + 1) % 3]);
                match by_edge.get(&key).and_then(|o| o.iter().find(|&&j| j != ti)) {
                    Some(&j) => ti = j,
                    None => break,
                }
            }
            // A point on an edge, or one the walk cannot reach, is left out.
            let found = found.filter(|&ti| strictly_inside(tris[ti], p, uv));
            let Some(ti) = found else {
                continue;
            };
            let [a, b, c] = tris[ti];
            let i = uv.len() as u32;
            uv.push(p);
            xyz.push(surf.point(p));
            let (n1, n2) = (tris.len(), tris.len() + 1);
            tris[ti] = [a, b, i];
            tris.push([b, c, i]);
            tris.push([c, a, i]);
            let mut moved = |e: (u32, u32), to: usize| {
                if let Some(o) = by_edge.get_mut(&e) {
                    for x in o.iter_mut().filter(|x| **x == ti) {
                        *x = to;
                    }
                }
            };
            moved(edge_key(b, c), n1);
            moved(edge_key(c, a), n2);
            by_edge.insert(edge_key(a, i), vec![ti, n2]);
            by_edge.insert(edge_key(b, i), vec![ti, n1]);
            by_edge.insert(edge_key(c, i), vec![n1, n2]);
            last = ti;
        }
    }
}

/// The unit normal of `surf` at `uv` (central differences); zero where it is not defined.
fn normal(surf: &Surface, uv: DVec2) -> DVec3 {
    let h = 1e-6;
    let du = surf.point(uv + DVec2::new(h, 0.0)) - surf.point(uv - DVec2::new(h, 0.0));
    let dv = surf.point(uv + DVec2::new(0.0, h)) - surf.point(uv - DVec2::new(0.0, h));
    du.cross(dv).try_normalize().unwrap_or(DVec3::ZERO)
}

/// True when triangle `t` is a sliver in `uv`.
fn is_sliver(uv: &[DVec2], t: [u32; 3]) -> bool {
    let [a, b, c] = t.map(|i| uv[i as usize]);
    let longest = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    (b - a).perp_dot(c - a).abs() <= SLIVER * longest
}

/// Removes slivers (the ear clipper's triangles along a bound that is straight in (u, v) up
/// to rounding, which would fold back across the bound in space) by flipping their longest
/// edge where it is an inner edge and both new triangles turn counter-clockwise.
fn flip_slivers(uv: &[DVec2], tris: &mut [[u32; 3]], boundary: &rustc_hash::FxHashSet<(u32, u32)>) {
    let ccw = |t: [u32; 3]| {
        let [a, b, c] = t.map(|i| uv[i as usize]);
        (b - a).perp_dot(c - a) > 0.0
    };
    for _ in 0..MAX_PASSES * 4 {
        let mut by_edge: FxHashMap<(u32, u32), Vec<usize>> = FxHashMap::default();
        for (i, t) in tris.iter().enumerate() {
            for k in 0..3 {
                by_edge
                    .entry(edge_key(t[k], t[(k + 1) % 3]))
                    .or_default()
                    .push(i);
            }
        }
        let mut touched = vec![false; tris.len()];
        let mut flipped = false;
        for ti in 0..tris.len() {
            let t = tris[ti];
            if touched[ti] || !is_sliver(uv, t) {
                continue;
            }
            let len = |k: usize| uv[t[k] as usize].distance_squared(uv[t[(k + 1) % 3] as usize]);
            let k = (0..3)
                .max_by(|&x, &y| len(x).total_cmp(&len(y)))
                .unwrap_or(0);
            let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let key = edge_key(a, b);
            if boundary.contains(&key) {
                continue;
            }
            let Some(&tj) = by_edge[&key].iter().find(|&&j| j != ti) else {
                continue;
            };
            if touched[tj] {
                continue;
            }
            let Some(&d) = tris[tj].iter().find(|&&v| v != a && v != b) else {
                continue;
            };
            let (n1, n2) = ([a, d, c], [d, b, c]);
            if ccw(n1) && ccw(n2) {
                tris[ti] = n1;
                tris[tj] = n2;
                touched[ti] = true;
                touched[tj] = true;
                flipped = true;
            }
        }
        if !flipped {
            break;
        }
    }
}

/// Red-green refinement of `tris` (indices into `uv` / `xyz`, counter-clockwise in uv):
/// inner edges whose sagitta on `surf` breaks the chord rule, or across which the surface
/// turns by more than [`MAX_ARC_STEP`] (the arc rule for a long edge along a cylinder's
/// axis that crosses a few degrees of it), both with [`INNER_SLACK`], are split at their
/// middle in uv, except edges of slivers; `None` past [`MAX_FACE_TRIANGLES`].
fn refine(
    surf: &Surface,
    uv: &mut Vec<DVec2>,
    xyz: &mut Vec<DVec3>,
    mut tris: Vec<[u32; 3]>,
    boundary: &rustc_hash::FxHashSet<(u32, u32)>,
) -> Option<Vec<[u32; 3]>> {
    for _ in 0..MAX_PASSES {
        // Edges of slivers (the ear clipper's triangles along a bound that is straight in
        // (u, v) up to rounding) are left alone: they hug the bound, and their middle would
        // fall on a point of it.
        let mut sliver_edges: rustc_hash::FxHashSet<(u32, u32)> = Default::default();
        for t in &tris {
            if is_sliver(uv, *t) {
                for k in 0..3 {
                    sliver_edges.insert(edge_key(t[k], t[(k + 1) % 3]));
                }
            }
        }
        let mut split: FxHashMap<(u32, u32), u32> = FxHashMap::default();
        for t in &tris {
            for k in 0..3 {
                let key = edge_key(t[k], t[(k + 1) % 3]);
                if boundary.contains(&key)
                    || sliver_edges.contains(&key)
                    || split.contains_key(&key)
                {
                    continue;
                }
                let (a, b) = (key.0 as usize, key.1 as usize);
                let m = (uv[a] + uv[b]) / 2.0;
                let pm = surf.point(m);
                let sag = (pm - (xyz[a] + xyz[b]) / 2.0).length();
                let coarse = sag > MIN_SAG
                    && (sag > MAX_SAG_RATIO * INNER_SLACK * xyz[a].distance(xyz[b]) || {
                        let (na, nb) = (normal(surf, uv[a]), normal(surf, uv[b]));
                        na.angle_between(nb) > MAX_ARC_STEP * INNER_SLACK
                    });
                if coarse {
                    uv.push(m);
                    xyz.push(pm);
                    split.insert(key, uv.len() as u32 - 1);
                }
            }
        }
        if split.is_empty() {
            return Some(tris);
        }
        let mut next = Vec::with_capacity(tris.len() * 2);
        for t in &tris {
            let mid = |k: usize| split.get(&edge_key(t[k], t[(k + 1) % 3])).copied();
            let m = [mid(0), mid(1), mid(2)];
            match m.iter().filter(|x| x.is_some()).count() {
                0 => next.push(*t),
                3 => {
                    let [ab, bc, ca] = m.map(|x| x.expect("three splits"));
                    next.extend([[t[0], ab, ca], [ab, t[1], bc], [ca, bc, t[2]], [ab, bc, ca]]);
                }
                1 => {
                    let k = (0..3).find(|&k| m[k].is_some()).expect("one split");
                    let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                    let x = m[k].expect("split");
                    next.extend([[a, x, c], [x, b, c]]);
                }
                _ => {
                    // The unsplit edge is c-a: split a-b at x and b-c at y.
                    let k = (0..3).find(|&k| m[k].is_none()).expect("one unsplit");
                    let (a, b, c) = (t[(k + 1) % 3], t[(k + 2) % 3], t[k]);
                    let x = m[(k + 1) % 3].expect("split");
                    let y = m[(k + 2) % 3].expect("split");
                    next.extend([[x, b, y], [a, x, y], [a, y, c]]);
                }
            }
        }
        tris = next;
        if tris.len() > MAX_FACE_TRIANGLES {
            return None;
        }
    }
    Some(tris)
}
